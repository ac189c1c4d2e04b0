// The main window's menus (File, Review, View, Help), its toolbar, the zoom actions and the list
// of keyboard shortcuts Help shows: MainWindow's commands, apart from its views and data.
#include <QAction>
#include <QDockWidget>
#include <QKeySequence>
#include <QMenuBar>
#include <QMessageBox>
#include <QToolBar>

#include "ui/export_menu.h"
#include "ui/main_window.h"
#include "ui/plots/plot_theme.h"
#include "ui/plots/plot_zoom.h"
#include "ui/review/record_view.h"
#include "ui/review/review_view.h"

namespace oscilab::ui {

void MainWindow::build_menus(QDockWidget* dock) {
  QMenu* file_menu = menuBar()->addMenu(tr("&File"));
  open_action_ = file_menu->addAction(tr("&Open\u2026"), this, &MainWindow::choose_and_open);
  open_action_->setShortcut(QKeySequence::Open);
  open_action_->setToolTip(tr("Open one or several recordings (Ctrl+O)"));
  open_session_action_ =
      file_menu->addAction(tr("Open &session\u2026"), this, &MainWindow::choose_and_open_session);
  save_session_action_ =
      file_menu->addAction(tr("Save session\u2026"), this, &MainWindow::choose_and_save_session);
  save_session_action_->setShortcut(QKeySequence::Save);
  export_menu_ = new ExportMenu(this, file_menu);
  file_menu->addSeparator();
  quit_action_ = file_menu->addAction(tr("&Quit"), this, &QWidget::close);
  quit_action_->setShortcut(QKeySequence::Quit);

  QMenu* review_menu = menuBar()->addMenu(tr("&Review"));
  mark_action_ =
      review_menu->addAction(tr("&Mark at cursor\u2026"), this, &MainWindow::mark_at_cursor);
  mark_action_->setShortcut(Qt::CTRL | Qt::Key_M);
  mark_action_->setToolTip(tr("Add a note at the cursor time (Ctrl+M)"));
  review_menu->addSeparator();
  next_level_action_ = review_menu->addAction(tr("&Next level"), this, [this] { step_level(1); });
  next_level_action_->setShortcut(Qt::ALT | Qt::Key_Down);
  previous_level_action_ =
      review_menu->addAction(tr("&Previous level"), this, [this] { step_level(-1); });
  previous_level_action_->setShortcut(Qt::ALT | Qt::Key_Up);

  RecordView* records = review_view_->record_view();
  QMenu* view_menu = menuBar()->addMenu(tr("&View"));
  view_menu->addAction(dock->toggleViewAction());
  fit_action_ = view_menu->addAction(tr("&Whole record"), records, &RecordView::fit);
  fit_action_->setToolTip(tr("Show the whole record (also: double-click the plot, or Ctrl+0)"));
  auto_value_range_action_ = view_menu->addAction(tr("Fit &values to the time window"));
  auto_value_range_action_->setCheckable(true);
  auto_value_range_action_->setChecked(records->auto_value_range());
  auto_value_range_action_->setToolTip(
      tr("Value axes follow the data in view; off: they keep the whole record's range"));
  connect(auto_value_range_action_, &QAction::toggled, records, &RecordView::set_auto_value_range);
  cursor_follows_mouse_action_ = view_menu->addAction(tr("&Cursor follows the mouse"));
  cursor_follows_mouse_action_->setCheckable(true);
  cursor_follows_mouse_action_->setChecked(records->cursor_follows_mouse());
  cursor_follows_mouse_action_->setToolTip(
      tr("Off (after a click or a level selection): the cursor stays where it was put"));
  connect(cursor_follows_mouse_action_, &QAction::toggled, records,
          &RecordView::set_cursor_follows_mouse);
  connect(records, &RecordView::cursor_follows_mouse_changed, cursor_follows_mouse_action_,
          &QAction::setChecked);
  view_menu->addSeparator();
  add_zoom_actions(view_menu);
  add_theme_menu(*view_menu);  // plots follow the palette (PlotPalettes, below)

  QMenu* help_menu = menuBar()->addMenu(tr("&Help"));
  help_menu->addAction(tr("&Keyboard shortcuts"), this, [this] {
    QMessageBox::information(this, tr("Keyboard shortcuts"), shortcut_lines().join('\n'));
  });
}

void MainWindow::build_toolbar() {
  QToolBar* tools = addToolBar(tr("Main"));
  tools->setObjectName("main_toolbar");
  tools->setMovable(false);
  tools->addAction(open_action_);
  tools->addAction(fit_action_);
  tools->addAction(mark_action_);
}

void MainWindow::add_zoom_actions(QMenu* menu) {
  // The plot under the mouse, or the one it was over last, or the first one shown.
  const auto on_plot = [this](void (*act)(QCustomPlot&)) {
    return [this, act] {
      if (QCustomPlot* plot = export_menu_->plot_to_export()) act(*plot);
    };
  };
  constexpr double kZoomStep = 1.25;  // per key press, like three notches of the wheel
  zoom_in_action_ = menu->addAction(
      tr("Zoom &in"), this, on_plot([](QCustomPlot& plot) { zoom_plot(plot, 1.0 / kZoomStep); }));
  zoom_in_action_->setShortcuts({QKeySequence::ZoomIn, Qt::CTRL | Qt::Key_Equal});
  zoom_out_action_ = menu->addAction(
      tr("Zoom &out"), this, on_plot([](QCustomPlot& plot) { zoom_plot(plot, kZoomStep); }));
  zoom_out_action_->setShortcuts(QKeySequence::ZoomOut);
  reset_zoom_action_ = menu->addAction(tr("&Reset zoom"), this, [this] {
    QCustomPlot* plot = export_menu_->plot_to_export();
    if (!plot || plot == record_view()->plot()) {
      record_view()->fit();  // the record view keeps its time window itself
    } else {
      reset_plot_zoom(*plot);
    }
  });
  reset_zoom_action_->setShortcut(Qt::CTRL | Qt::Key_0);
  undo_zoom_action_ = menu->addAction(tr("&Undo zoom"), this,
                                      on_plot([](QCustomPlot& plot) { undo_plot_zoom(plot); }));
  undo_zoom_action_->setShortcuts({QKeySequence::Undo, Qt::Key_Backspace});
}

QStringList MainWindow::shortcut_lines() const {
  QStringList lines;
  for (QAction* top : menuBar()->actions()) {
    if (!top->menu()) continue;
    const QString menu = top->menu()->title().remove('&');
    for (QAction* action : top->menu()->actions()) {
      if (action->shortcuts().isEmpty()) continue;
      QStringList keys;
      for (const QKeySequence& key : action->shortcuts()) {
        keys << key.toString(QKeySequence::NativeText);
      }
      lines << tr("%1 \u25b8 %2: %3")
                   .arg(menu, action->text().remove('&').remove(QChar(0x2026)), keys.join(", "));
    }
  }
  return lines;
}

}  // namespace oscilab::ui

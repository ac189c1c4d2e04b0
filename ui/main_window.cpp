#include "ui/main_window.h"

#include <exception>

#include <QAction>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>
#include <QToolBar>

#include "analysis/common/input_error.h"
#include "ui/identification_panel.h"
#include "ui/record_view.h"

namespace oscilab::ui {
namespace {

// "2 channels, 512 Hz, 262.00 s (134144 samples), stepped-sine at 9 Hz".
QString summary(const daq::Recording& recording) {
  const auto channels = recording.sidecar.channels.size();
  const double rate_hz = recording.sidecar.sample_rate_hz;
  const double duration_s = rate_hz > 0.0 ? double(recording.sample_count()) / rate_hz : 0.0;
  QString text = QObject::tr("%1 %2, %3 Hz, %4 s (%5 samples)")
                     .arg(channels)
                     .arg(channels == 1 ? QObject::tr("channel") : QObject::tr("channels"))
                     .arg(rate_hz, 0, 'g', 6)
                     .arg(duration_s, 0, 'f', 2)
                     .arg(recording.sample_count());
  if (const auto& excitation = recording.sidecar.excitation;
      excitation && !excitation->type.empty()) {
    text += ", " + QString::fromStdString(excitation->type);
    if (excitation->frequency_hz) {
      text += QObject::tr(" at %1 Hz").arg(*excitation->frequency_hz, 0, 'g', 6);
    }
  }
  return text;
}

}  // namespace

MainWindow::MainWindow(QWidget* parent, Loader loader)
    : QMainWindow(parent), loader_(std::move(loader)) {
  if (!loader_) loader_ = [](const std::string& path) { return daq::read_recording(path); };

  record_view_ = new RecordView(this);
  setCentralWidget(record_view_);
  identification_panel_ = new IdentificationPanel(this);
  auto* dock = new QDockWidget(tr("Fit and diagnosis"), this);
  dock->setObjectName("identification_dock");
  dock->setWidget(identification_panel_);
  identification_panel_->setMinimumWidth(520);
  addDockWidget(Qt::RightDockWidgetArea, dock);

  QMenu* file_menu = menuBar()->addMenu(tr("&File"));
  open_action_ = file_menu->addAction(tr("&Open\u2026"), this, &MainWindow::choose_and_open);
  open_action_->setShortcut(QKeySequence::Open);
  file_menu->addSeparator();
  quit_action_ = file_menu->addAction(tr("&Quit"), this, &QWidget::close);
  quit_action_->setShortcut(QKeySequence::Quit);

  QMenu* view_menu = menuBar()->addMenu(tr("&View"));
  view_menu->addAction(dock->toggleViewAction());
  fit_action_ = view_menu->addAction(tr("&Whole record"), record_view_, &RecordView::fit);
  fit_action_->setShortcut(Qt::CTRL | Qt::Key_0);
  fit_action_->setToolTip(tr("Show the whole record (also: double-click the plot)"));
  auto_value_range_action_ = view_menu->addAction(tr("Fit &values to the time window"));
  auto_value_range_action_->setCheckable(true);
  auto_value_range_action_->setChecked(record_view_->auto_value_range());
  auto_value_range_action_->setToolTip(
      tr("Value axes follow the data in view; off: they keep the whole record's range"));
  connect(auto_value_range_action_, &QAction::toggled, record_view_,
          &RecordView::set_auto_value_range);

  QToolBar* tools = addToolBar(tr("Main"));
  tools->setObjectName("main_toolbar");
  tools->setMovable(false);
  tools->addAction(open_action_);
  tools->addAction(fit_action_);

  setWindowTitle(tr("Oscilab"));
  statusBar()->showMessage(tr("Open a recording with File \u25b8 Open (Ctrl+O)."));
  resize(1500, 900);
}

MainWindow::~MainWindow() = default;

bool MainWindow::open_recording(const QString& path) {
  const std::string path_utf8 = path.toStdString();
  try {
    auto recording = std::make_shared<daq::Recording>(loader_(path_utf8));
    if (recording->source_path.empty()) recording->source_path = path_utf8;
    show_recording(std::move(recording));
  } catch (const InputError& error) {
    report_error(QString::fromStdString(error.what()));
    return false;
  } catch (const std::exception& error) {
    report_error(tr("%1: cannot be read: %2").arg(path, QString::fromStdString(error.what())));
    return false;
  }
  last_directory_ = QFileInfo(path).absolutePath();
  identification_panel_->add_recording(path_utf8);
  Q_EMIT recording_opened(path);
  return true;
}

void MainWindow::show_recording(std::shared_ptr<const daq::Recording> recording) {
  if (!recording) return;
  const QString name = recording->source_path.empty()
                           ? tr("untitled")
                           : QFileInfo(QString::fromStdString(recording->source_path)).fileName();
  const QString text = name + ": " + summary(*recording);
  record_view_->set_recording(std::move(recording));
  setWindowTitle(tr("%1 \u2014 Oscilab").arg(name));
  statusBar()->showMessage(text);
}

void MainWindow::choose_and_open() {
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Open recording"), last_directory_,
      tr("Recordings (*.wav *.flac *.w64 *.rf64 *.aiff *.aif *.caf *.csv);;All files (*)"));
  if (!path.isEmpty()) open_recording(path);
}

void MainWindow::report_error(const QString& message) {
  statusBar()->showMessage(tr("Error: %1").arg(message));
  Q_EMIT error_reported(message);
  if (interactive_errors_) QMessageBox::critical(this, tr("Cannot open recording"), message);
}

}  // namespace oscilab::ui

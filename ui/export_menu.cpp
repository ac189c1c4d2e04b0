#include "ui/export_menu.h"

#include <exception>
#include <memory>
#include <string>

#include <QAction>
#include <QApplication>
#include <QCursor>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QMessageBox>
#include <QStatusBar>
#include <QTabWidget>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "daq/export/mat_export.h"
#include "daq/export/uff58_export.h"
#include "ui/background_job.h"
#include "ui/main_window.h"
#include "ui/plots/plot_context_menu.h"
#include "ui/plots/plot_export.h"
#include "ui/review/level_table.h"
#include "ui/review/record_view.h"
#include "ui/review/review_model.h"
#include "ui/review/review_view.h"

namespace oscilab::ui {
namespace {

bool shown(const QCustomPlot* plot) {
  return plot != nullptr && plot->isVisible() && plot->width() > 0 && plot->height() > 0;
}

QCustomPlot* first_shown_plot(QWidget* root) {
  if (root == nullptr) return nullptr;
  for (QCustomPlot* plot : root->findChildren<QCustomPlot*>()) {
    if (shown(plot)) return plot;
  }
  return nullptr;
}

}  // namespace

ExportMenu::ExportMenu(MainWindow* window, QMenu* file_menu) : QObject(window), window_(window) {
  context_menus_ = new PlotContextMenus(this);
  job_ = new BackgroundJob(this);
  menu_ = file_menu->addMenu(tr("&Export"));
  menu_->setObjectName("export_menu");
  plot_action_ = menu_->addAction(tr("&Plot as PNG/SVG/PDF\u2026"), this, [this] {
    const QCustomPlot* plot = plot_to_export();
    const QString path = ask_path(tr("Export plot"),
                                  (plot ? plot_file_name(*plot) : QStringLiteral("plot")) + ".png",
                                  tr("PNG image (*.png);;SVG drawing (*.svg);;PDF document "
                                     "(*.pdf)"));
    if (!path.isEmpty()) export_plot(path);
  });
  plot_action_->setToolTip(
      tr("The plot under the mouse or hovered last, else the first plot of the current tab "
         "(also: right-click a plot)"));
  table_action_ = menu_->addAction(tr("Level &table as CSV\u2026"), this, [this] {
    const QString path = ask_path(tr("Export level table"), "levels.csv", tr("CSV (*.csv)"));
    if (!path.isEmpty()) export_level_table(path);
  });
  menu_->addSeparator();
  mat_action_ = menu_->addAction(tr("Recording as &MATLAB .mat\u2026"), this, [this] {
    const QString path =
        ask_path(tr("Export recording as MATLAB"), "recording.mat", tr("MATLAB MAT-file (*.mat)"));
    if (!path.isEmpty()) export_recording_mat(path);
  });
  uff_action_ = menu_->addAction(tr("Recording as &UFF 58\u2026"), this, [this] {
    const QString path = ask_path(tr("Export recording as UFF 58"), "recording.uff",
                                  tr("Universal File (*.uff *.unv)"));
    if (!path.isEmpty()) export_recording_uff(path);
  });
  edc_mat_action_ = menu_->addAction(tr("&EDC table as .mat\u2026"), this, [this] {
    const QString path =
        ask_path(tr("Export EDC table as MATLAB"), "edc.mat", tr("MATLAB MAT-file (*.mat)"));
    if (!path.isEmpty()) export_edc_mat(path);
  });
}

// The worker holds shared copies of what it writes; it must end before the menu goes.
ExportMenu::~ExportMenu() { delete job_; }

bool ExportMenu::busy() const { return job_->running(); }

QString ExportMenu::ask_path(const QString& title, const QString& name, const QString& filter) {
  return QFileDialog::getSaveFileName(window_, title, name, filter);
}

QCustomPlot* ExportMenu::plot_to_export() const {
  if (auto* under = qobject_cast<QCustomPlot*>(QApplication::widgetAt(QCursor::pos()));
      shown(under)) {
    return under;
  }
  if (QCustomPlot* hovered = context_menus_->last_hovered(); shown(hovered)) return hovered;
  if (QCustomPlot* in_tab = first_shown_plot(window_->central_tabs()->currentWidget())) {
    return in_tab;
  }
  return first_shown_plot(window_);
}

void ExportMenu::succeed(const QString& path) {
  const QString message = tr("Exported to %1").arg(path);
  window_->statusBar()->showMessage(message);
  Q_EMIT export_finished(message, true);
}

bool ExportMenu::fail(const QString& message) {
  window_->statusBar()->showMessage(tr("Error: %1").arg(message));
  Q_EMIT window_->error_reported(message);
  if (window_->interactive_errors()) QMessageBox::critical(window_, tr("Export failed"), message);
  Q_EMIT export_finished(message, false);
  return false;
}

bool ExportMenu::export_plot(const QString& path) {
  QCustomPlot* plot = plot_to_export();
  if (plot == nullptr) return fail(tr("%1: no plot is shown to export").arg(path));
  try {
    ui::export_plot(*plot, path);
  } catch (const InputError& error) {
    return fail(QString::fromStdString(error.what()));
  }
  succeed(path);
  return true;
}

bool ExportMenu::export_level_table(const QString& path) {
  try {
    export_table_csv(*window_->review_view()->level_table(), path);
  } catch (const InputError& error) {
    return fail(QString::fromStdString(error.what()));
  }
  succeed(path);
  return true;
}

bool ExportMenu::export_recording_mat(const QString& path) {
  return write_file(FileKind::RecordingMat, path);
}
bool ExportMenu::export_recording_uff(const QString& path) {
  return write_file(FileKind::RecordingUff, path);
}
bool ExportMenu::export_edc_mat(const QString& path) { return write_file(FileKind::EdcMat, path); }

bool ExportMenu::write_file(FileKind kind, const QString& path) {
  if (job_->running()) return fail(tr("%1: another export is being written").arg(path));
  // What the worker writes, shared (never the widgets' own objects).
  std::shared_ptr<const daq::OpenedRecording> recording;
  std::shared_ptr<const ReviewAnalysis> analysis = window_->analysis();
  if (kind == FileKind::EdcMat) {
    if (!analysis) return fail(tr("%1: no analysis yet: open stepped-sine recordings").arg(path));
  } else {
    const daq::OpenedRecording* shown_recording = window_->record_view()->recording();
    if (shown_recording == nullptr) return fail(tr("%1: no recording is shown").arg(path));
    // A copy of the handle: the samples are shared, read whole by the worker.
    recording = std::make_shared<const daq::OpenedRecording>(*shown_recording);
  }
  auto error = std::make_shared<std::string>();
  const std::string file = path.toStdString();
  connect(
      job_, &BackgroundJob::finished, this,
      [this, error, path](bool) {
        if (!error->empty()) {
          fail(QString::fromStdString(*error));
        } else {
          succeed(path);
        }
      },
      Qt::SingleShotConnection);
  window_->statusBar()->showMessage(tr("Writing %1\u2026").arg(path));
  job_->start([kind, recording, analysis, error, file](const ProgressFn&, const CancelToken&) {
    try {
      switch (kind) {
        case FileKind::RecordingMat:
          daq::write_recording_mat(recording->samples->whole(), file);
          break;
        case FileKind::RecordingUff:
          daq::write_recording_uff58(recording->samples->whole(), file);
          break;
        case FileKind::EdcMat:
          daq::write_edc_mat(daq::edc_table_rows(analysis->campaign), file);
          break;
      }
    } catch (const std::exception& e) {  // InputError names the file; nothing crosses threads
      *error = e.what();
    }
  });
  return true;
}

}  // namespace oscilab::ui

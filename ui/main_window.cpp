#include "ui/main_window.h"

#include <algorithm>
#include <exception>

#include <QAction>
#include <QByteArray>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QGuiApplication>
#include <QInputDialog>
#include <QLabel>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QScreen>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>

#include "analysis/common/input_error.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/identification/edc_objective.h"
#include "daq/recording/format_reader.h"
#include "ui/background_job.h"
#include "ui/export_menu.h"
#include "ui/identification/identification_panel.h"
#include "ui/live/live_monitor.h"
#include "ui/plots/plot_hover_readout.h"
#include "ui/plots/plot_theme.h"
#include "ui/plots/plot_zoom.h"
#include "ui/review/channel_mapping_dialog.h"
#include "ui/review/dropped_files.h"
#include "ui/review/level_table.h"
#include "ui/review/record_view.h"
#include "ui/review/recording_opener.h"
#include "ui/review/review_model.h"
#include "ui/review/review_view.h"

namespace oscilab::ui {

/// A recording the window has opened, with the absolute path it came from.
struct MainWindow::OpenedFile {
  QString path;
  std::shared_ptr<const daq::OpenedRecording> recording;
};

namespace {

const QString kRecordingFilter = QObject::tr(
    "Recordings (*.wav *.flac *.w64 *.rf64 *.aiff *.aif *.caf *.csv *.tdms *.uff *.unv *.mat "
    "*.h5 *.hdf5);;All files (*)");
const QString kSessionFilter = QObject::tr("Oscilab sessions (*.json);;All files (*)");

// "2 channels, 512 Hz, 262.00 s (134144 samples), stepped-sine at 9 Hz".
QString summary(const daq::OpenedRecording& recording) {
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

// A random or other non-stepped record has no levels to fit: it stays out of the fit panel. A
// record that does not say its excitation joins (the analysis finds its levels, or not).
bool joins_fit(const daq::OpenedRecording& recording) {
  const auto& excitation = recording.sidecar.excitation;
  return !excitation || excitation->type.empty() || excitation->type == "stepped-sine";
}

}  // namespace

MainWindow::MainWindow(QWidget* parent, Loader loader)
    : QMainWindow(parent), loader_(std::move(loader)) {
  if (!loader_) {
    loader_ = [](const std::string& path, const daq::OpeningControl& control) {
      return daq::open_recording_for_review(path, control);
    };
  }
  mapping_asker_ = [this](const QString& path,
                          const daq::FileContents& contents) -> std::optional<daq::Sidecar> {
    ChannelMappingDialog dialog(path, contents, this);
    if (dialog.exec() != QDialog::Accepted) return std::nullopt;
    return dialog.sidecar();
  };
  QDockWidget* dock = build_views();
  build_status_bar();
  build_menus(dock);
  build_toolbar();
  connect(review_view_, &ReviewView::recording_shown, this, &MainWindow::update_title);

  setWindowTitle(tr("Oscilab"));
  statusBar()->showMessage(tr("Open recordings with File \u25b8 Open (Ctrl+O)."));
  // 1500×900, or less on a smaller screen: the window never starts larger than the screen.
  QSize size(1500, 900);
  if (const QScreen* screen = QGuiApplication::primaryScreen()) {
    size = size.boundedTo(screen->availableGeometry().size());
  }
  resize(size);
  // The panel takes about two fifths of the width, the review the rest.
  resizeDocks({dock}, {std::max(400, size.width() * 2 / 5)}, Qt::Horizontal);
  setAcceptDrops(true);
  new PlotHoverReadouts(this);  // the value under the mouse on every plot
  new PlotPalettes(this);
}

QDockWidget* MainWindow::build_views() {
  review_view_ = new ReviewView;
  central_tabs_ = new QTabWidget(this);
  central_tabs_->setObjectName("central_tabs");
  central_tabs_->setDocumentMode(true);
  central_tabs_->addTab(review_view_, tr("Review"));
  // The live monitor; it keeps the session's "live" settings.
  live_monitor_ = new LiveMonitor;
  live_monitor_->setObjectName("live_monitor");
  central_tabs_->addTab(live_monitor_, tr("Live"));
  setCentralWidget(central_tabs_);
  identification_panel_ = new IdentificationPanel(this);
  auto* dock = new QDockWidget(tr("Fit and diagnosis"), this);
  dock->setObjectName("identification_dock");
  dock->setWidget(identification_panel_);
  identification_panel_->setMinimumWidth(360);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  // From the rig to a fitted model: a finished live recording opens for review and is offered to
  // the fit set (it joins only when the user says so), and each fitted model's EDC is drawn over
  // the live measurement.
  connect(live_monitor_, &LiveMonitor::recording_finished, this, &MainWindow::open_live_recording);
  connect(identification_panel_, &IdentificationPanel::model_fitted, live_monitor_,
          [this](std::shared_ptr<const analysis::Model> model) {
            live_monitor_->set_prediction_model(std::move(model), tr("fitted model"));
          });
  return dock;
}

void MainWindow::build_status_bar() {
  analysis_job_ = new BackgroundJob(this);
  analysis_timer_ = new QTimer(this);
  analysis_timer_->setSingleShot(true);
  analysis_timer_->setInterval(0);
  connect(analysis_timer_, &QTimer::timeout, this, &MainWindow::start_analysis);
  connect(analysis_job_, &BackgroundJob::finished, this, &MainWindow::on_analysis_finished);
  analysis_label_ = new QLabel;
  analysis_label_->setObjectName("analysis_status");
  analysis_progress_ = new QProgressBar;
  analysis_progress_->setRange(0, 1000);
  analysis_progress_->setMaximumWidth(160);
  analysis_progress_->setTextVisible(false);
  analysis_progress_->hide();
  fit_set_offer_ = new QPushButton;
  fit_set_offer_->setObjectName("fit_set_offer");
  fit_set_offer_->setToolTip(tr("Add the recordings just made to the fit and diagnosis panel"));
  fit_set_offer_->hide();
  connect(fit_set_offer_, &QPushButton::clicked, this, [this] {
    for (const QString& path : offered_paths_)
      identification_panel_->add_recording(path.toStdString());
    fit_set_offer_->hide();
    statusBar()->showMessage(tr("Added to the fit set: %1").arg(offered_paths_.join(", ")));
    offered_paths_.clear();
  });
  statusBar()->addPermanentWidget(fit_set_offer_);
  statusBar()->addPermanentWidget(analysis_label_);
  statusBar()->addPermanentWidget(analysis_progress_);
  connect(analysis_job_, &BackgroundJob::progress, this, [this](double fraction) {
    analysis_progress_->setValue(static_cast<int>(1000 * fraction));
  });
}

void MainWindow::step_level(int step) {
  LevelTable* table = review_view_->level_table();
  const int rows = table->rowCount();
  if (rows == 0) return;
  const int current = table->currentRow();
  const int row = current < 0 ? (step > 0 ? 0 : rows - 1) : std::clamp(current + step, 0, rows - 1);
  review_view_->select_levels({table->key_at(row)});
}

void MainWindow::open_live_recording(const QString& path) {
  QString error;
  const LoadOutcome outcome = load(path, error, false);
  if (outcome == LoadOutcome::Failed) report_error(error, tr("Cannot open recording"));
  if (outcome != LoadOutcome::Opened) return;
  Q_EMIT recording_opened(path);
  const QString absolute = QFileInfo(path).absoluteFilePath();
  bool fits = false;
  for (const OpenedFile& opened : opened_) {
    if (opened.path == absolute) fits = joins_fit(*opened.recording);
  }
  if (!fits) {
    statusBar()->showMessage(tr("Recorded %1: opened for review").arg(path));
    return;
  }
  if (!offered_paths_.contains(path)) offered_paths_ << path;  // each recording until added
  fit_set_offer_->setText(offered_paths_.size() == 1
                              ? tr("Add %1 to the fit set").arg(QFileInfo(path).fileName())
                              : tr("Add %1 recordings to the fit set").arg(offered_paths_.size()));
  fit_set_offer_->show();
  statusBar()->showMessage(tr("Recorded %1: opened for review, not in the fit set").arg(path));
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  const DroppedFiles files = sort_dropped_files(event->mimeData()->urls());
  if (!files.sessions.isEmpty() || !files.recordings.isEmpty()) event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  const DroppedFiles files = sort_dropped_files(event->mimeData()->urls());
  if (files.sessions.isEmpty() && files.recordings.isEmpty()) return;
  event->acceptProposedAction();
  // Opened after the drop has ended (a file without a sidecar asks in a dialog). A session
  // replaces the review: the last one dropped; recordings dropped with it join it.
  QTimer::singleShot(0, this, [this, files] {
    if (!files.sessions.isEmpty()) open_session(files.sessions.last());
    if (!files.recordings.isEmpty()) open_recordings(files.recordings);
  });
}

MainWindow::~MainWindow() = default;

RecordView* MainWindow::record_view() const { return review_view_->record_view(); }

bool MainWindow::analysis_running() const {
  return analysis_job_->running() || analysis_timer_->isActive();
}

MainWindow::LoadOutcome MainWindow::load(const QString& path, QString& error, bool join_fit) {
  const std::string path_utf8 = path.toStdString();
  std::shared_ptr<daq::OpenedRecording> recording;
  try {
    // A file another program wrote, without a sidecar: ask what its signals are, and keep the
    // answer as its sidecar.
    const std::string sidecar_path = daq::sidecar_path_for(path_utf8);
    if (QFileInfo(path).isFile() && !QFileInfo::exists(QString::fromStdString(sidecar_path)) &&
        QFileInfo(path).suffix().toLower() != "json") {
      const daq::FormatReader& format = daq::format_for_file(path_utf8);
      const std::optional<daq::Sidecar> sidecar = mapping_asker_(path, format.describe(path_utf8));
      if (!sidecar) {
        error = tr("%1: not opened: no sidecar says what its signals are").arg(path);
        return LoadOutcome::Failed;
      }
      daq::write_sidecar(*sidecar, sidecar_path);
    }
    recording = open_off_the_ui_thread(this, tr("Opening %1\u2026").arg(QFileInfo(path).fileName()),
                                       [this, &path_utf8](const daq::OpeningControl& control) {
                                         return loader_(path_utf8, control);
                                       });
    if (recording->source_path.empty()) recording->source_path = path_utf8;
  } catch (const daq::OpeningCancelled&) {
    error = tr("%1: opening cancelled").arg(path);
    return LoadOutcome::Cancelled;
  } catch (const InputError& input_error) {
    error = QString::fromStdString(input_error.what());
    return LoadOutcome::Failed;
  } catch (const std::exception& other) {
    error = tr("%1: cannot be read: %2").arg(path, QString::fromStdString(other.what()));
    return LoadOutcome::Failed;
  }
  const QString absolute = QFileInfo(path).absoluteFilePath();
  bool replaced = false;
  for (OpenedFile& opened : opened_) {
    if (opened.path == absolute) {
      opened.recording = recording;
      replaced = true;
    }
  }
  if (!replaced) opened_.push_back({absolute, recording});
  sync_recordings();
  show_recording(recording);
  last_directory_ = QFileInfo(path).absolutePath();
  if (join_fit && joins_fit(*recording)) identification_panel_->add_recording(path_utf8);
  schedule_analysis();
  return LoadOutcome::Opened;
}

bool MainWindow::open_recording(const QString& path) {
  QString error;
  const LoadOutcome outcome = load(path, error);
  if (outcome == LoadOutcome::Cancelled) statusBar()->showMessage(error);
  if (outcome == LoadOutcome::Failed) report_error(error, tr("Cannot open recording"));
  if (outcome != LoadOutcome::Opened) return false;
  Q_EMIT recording_opened(path);
  return true;
}

int MainWindow::open_recordings(const QStringList& paths) {
  std::shared_ptr<const daq::OpenedRecording> first;
  int opened = 0;
  for (const QString& path : paths) {
    if (!open_recording(path)) continue;
    ++opened;
    for (const OpenedFile& o : opened_) {
      if (!first && o.path == QFileInfo(path).absoluteFilePath()) first = o.recording;
    }
  }
  if (first) show_recording(first);
  return opened;
}

QStringList MainWindow::opened_paths() const {
  QStringList paths;
  for (const OpenedFile& opened : opened_) paths << opened.path;
  return paths;
}

void MainWindow::show_recording(std::shared_ptr<const daq::OpenedRecording> recording) {
  if (!recording) return;
  review_view_->show_recording(std::move(recording));
}

void MainWindow::update_title() {
  const daq::OpenedRecording* recording = record_view()->recording();
  if (!recording) {
    setWindowTitle(tr("Oscilab"));
    return;
  }
  const QString name = recording->source_path.empty()
                           ? tr("untitled")
                           : QFileInfo(QString::fromStdString(recording->source_path)).fileName();
  setWindowTitle(tr("%1 \u2014 Oscilab").arg(name));
  statusBar()->showMessage(name + ": " + summary(*recording));
}

void MainWindow::sync_recordings() {
  std::vector<ReviewView::Opened> recordings;
  for (const OpenedFile& opened : opened_) {
    recordings.push_back({opened.path.toStdString(), opened.recording});
  }
  review_view_->set_recordings(std::move(recordings));
}

void MainWindow::set_analysis_settings(const analysis::PipelineSettings& settings) {
  settings_ = settings;
  schedule_analysis();
}

void MainWindow::schedule_analysis() { analysis_timer_->start(); }

void MainWindow::start_analysis() {
  if (analysis_job_->running()) {  // the recordings changed: this result would be stale
    analysis_again_ = true;
    analysis_job_->cancel();
    return;
  }
  std::vector<std::shared_ptr<const daq::OpenedRecording>> recordings;
  for (const OpenedFile& opened : opened_) recordings.push_back(opened.recording);
  if (recordings.empty()) {
    analysis_.reset();
    review_view_->set_analysis(nullptr);
    analysis_label_->clear();
    return;
  }
  auto result = std::make_shared<ReviewAnalysis>();
  analysis_result_ = result;
  const analysis::PipelineSettings settings = settings_;
  analysis_progress_->setValue(0);
  analysis_progress_->show();
  analysis_label_->setText(tr("Analysing %1 %2\u2026")
                               .arg(recordings.size())
                               .arg(recordings.size() == 1 ? tr("recording") : tr("recordings")));
  review_view_->set_analysis_running(true);
  analysis_job_->start(
      [result, recordings, settings](const ProgressFn& progress, const CancelToken& cancel) {
        try {
          *result = analyze_review(recordings, settings, progress, cancel);
        } catch (const std::exception& error) {  // nothing may cross the thread
          result->errors.emplace_back(error.what());
          result->campaign.status = JobStatus::InvalidInput;
        }
      });
}

void MainWindow::on_analysis_finished(bool cancelled) {
  analysis_progress_->hide();
  if (analysis_again_) {
    analysis_again_ = false;
    start_analysis();
    return;
  }
  if (cancelled || !analysis_result_) {
    analysis_label_->setText(tr("Analysis cancelled"));
    return;
  }
  analysis_ = std::move(analysis_result_);
  review_view_->set_analysis(analysis_);
  std::size_t levels = 0;
  for (const analysis::RecordAnalysis& record : analysis_->campaign.records) {
    levels += record.levels.size();
  }
  const std::size_t records = analysis_->campaign.records.size();
  QString text = tr("Analysis: %1 %2, %3 %4")
                     .arg(records)
                     .arg(records == 1 ? tr("record") : tr("records"))
                     .arg(levels)
                     .arg(levels == 1 ? tr("level") : tr("levels"));
  if (!analysis_->errors.empty()) {
    text += tr(", %1 left out").arg(analysis_->errors.size());
    statusBar()->showMessage(tr("Analysis: %1").arg(QString::fromStdString(analysis_->errors[0])));
  }
  analysis_label_->setText(text);
  // The fit panel shows the measurement it would fit at once, before any fit.
  try {
    identification_panel_->show_measured(analysis::edc_dataset(analysis_->campaign));
  } catch (const InputError& error) {  // no usable stepped-sine level
    identification_panel_->show_measured({}, QString::fromStdString(error.what()));
  }

  // A session's selection, now that its levels exist.
  std::vector<LevelKey> keys;
  for (const Session::LevelRef& ref : pending_levels_) {
    for (std::size_t r = 0; r < analysis_->recordings.size(); ++r) {
      for (const OpenedFile& opened : opened_) {
        if (opened.recording == analysis_->recordings[r] &&
            opened.path.toStdString() == ref.recording) {
          keys.push_back({int(r), ref.level});
        }
      }
    }
  }
  pending_levels_.clear();
  if (!keys.empty()) review_view_->select_levels(keys, false);
  Q_EMIT analysis_finished();
}

Session MainWindow::current_session() const {
  Session session;
  for (const OpenedFile& opened : opened_) {
    session.recordings.push_back(opened.path.toStdString());
  }
  session.settings = settings_;
  session.window_geometry_base64 = saveGeometry().toBase64().toStdString();
  session.window_state_base64 = saveState().toBase64().toStdString();
  session.shown_recording = review_view_->shown_path();
  if (record_view()->recording()) {
    session.time_window = record_view()->time_window();
    session.cursor_s = record_view()->cursor_time();
  }
  if (!pending_levels_.empty()) {  // a session's selection whose analysis is not shown yet
    session.selected_levels = pending_levels_;
  } else if (analysis_) {
    for (const LevelKey& key : review_view_->selected_levels()) {
      if (key.record < 0 || std::size_t(key.record) >= analysis_->recordings.size()) continue;
      for (const OpenedFile& opened : opened_) {
        if (opened.recording == analysis_->recordings[std::size_t(key.record)]) {
          session.selected_levels.push_back({opened.path.toStdString(), key.level});
        }
      }
    }
  }
  session.annotations = review_view_->annotations();
  session.live = live_monitor_->session_settings();
  return session;
}

bool MainWindow::save_session(const QString& path) {
  try {
    write_session(current_session(), path.toStdString());
  } catch (const InputError& error) {
    report_error(QString::fromStdString(error.what()), tr("Cannot save session"));
    return false;
  }
  statusBar()->showMessage(tr("Session saved to %1").arg(path));
  return true;
}

bool MainWindow::open_session(const QString& path) {
  Session session;
  try {
    session = read_session(path.toStdString());
  } catch (const InputError& error) {
    report_error(QString::fromStdString(error.what()), tr("Cannot open session"));
    return false;
  }
  // The file is valid: replace the review by it.
  opened_.clear();
  analysis_.reset();
  pending_levels_.clear();
  settings_ = session.settings;
  if (!session.window_geometry_base64.empty()) {
    restoreGeometry(
        QByteArray::fromBase64(QByteArray::fromStdString(session.window_geometry_base64)));
  }
  if (!session.window_state_base64.empty()) {
    restoreState(QByteArray::fromBase64(QByteArray::fromStdString(session.window_state_base64)));
  }
  QStringList missing;
  for (const std::string& recording : session.recordings) {
    const QString file = QString::fromStdString(recording);
    QString error;
    if (!QFileInfo::exists(file)) {
      missing << tr("%1 (not found)").arg(QFileInfo(file).fileName());
    } else if (load(file, error) != LoadOutcome::Opened) {
      missing << error;
    }
  }
  sync_recordings();
  identification_panel_->set_recordings({});
  for (const OpenedFile& opened : opened_) {
    if (joins_fit(*opened.recording)) {
      identification_panel_->add_recording(opened.path.toStdString());
    }
  }
  const auto is_open = [this](const std::string& p) {
    for (const OpenedFile& opened : opened_) {
      if (opened.path.toStdString() == p) return true;
    }
    return false;
  };

  std::shared_ptr<const daq::OpenedRecording> shown =
      opened_.empty() ? nullptr : opened_[0].recording;
  for (const OpenedFile& opened : opened_) {
    if (opened.path.toStdString() == session.shown_recording) shown = opened.recording;
  }
  review_view_->set_analysis(nullptr);
  review_view_->show_recording(shown);
  if (shown && session.time_window) {
    record_view()->set_time_window(session.time_window->start_s, session.time_window->end_s);
  }
  if (shown && session.cursor_s) {
    record_view()->set_cursor_follows_mouse(false);
    record_view()->set_cursor_time(*session.cursor_s);
  }
  std::vector<Annotation> annotations;
  for (const Annotation& annotation : session.annotations) {
    if (is_open(annotation.recording)) annotations.push_back(annotation);
  }
  review_view_->set_annotations(std::move(annotations));
  for (const Session::LevelRef& level : session.selected_levels) {
    if (is_open(level.recording)) pending_levels_.push_back(level);
  }
  schedule_analysis();
  live_monitor_->apply_settings(session.live);
  if (!missing.isEmpty()) {
    report_error(tr("%1: recordings not opened: %2; the other %3 opened")
                     .arg(path, missing.join("; "))
                     .arg(opened_.size()),
                 tr("Session opened in part"));
  } else {
    statusBar()->showMessage(
        tr("Session %1: %2 recordings opened").arg(QFileInfo(path).fileName()).arg(opened_.size()));
  }
  return true;
}

void MainWindow::choose_and_open() {
  const QStringList paths =
      QFileDialog::getOpenFileNames(this, tr("Open recordings"), last_directory_, kRecordingFilter);
  if (!paths.isEmpty()) open_recordings(paths);
}

void MainWindow::choose_and_open_session() {
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Open session"), last_directory_, kSessionFilter);
  if (!path.isEmpty()) open_session(path);
}

void MainWindow::choose_and_save_session() {
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Save session"), QFileInfo(last_directory_, "session.json").filePath(),
      kSessionFilter);
  if (!path.isEmpty()) save_session(path);
}

void MainWindow::mark_at_cursor() {
  if (!record_view()->recording()) {
    statusBar()->showMessage(tr("Open a recording to mark it."));
    return;
  }
  const TimeWindow window = record_view()->time_window();
  const double t_s = record_view()->cursor_time().value_or(0.5 * (window.start_s + window.end_s));
  QString note = tr("mark %1").arg(review_view_->annotations().size() + 1);
  if (interactive_errors_) {
    bool ok = false;
    note = QInputDialog::getText(this, tr("Mark"), tr("Note at t = %1 s:").arg(t_s, 0, 'f', 3),
                                 QLineEdit::Normal, note, &ok);
    if (!ok) return;
  }
  if (review_view_->add_annotation(note)) {
    statusBar()->showMessage(tr("Marked \u201c%1\u201d at t = %2 s").arg(note).arg(t_s, 0, 'f', 3));
  }
}

void MainWindow::report_error(const QString& message, const QString& title) {
  statusBar()->showMessage(tr("Error: %1").arg(message));
  Q_EMIT error_reported(message);
  if (interactive_errors_) QMessageBox::critical(this, title, message);
}

}  // namespace oscilab::ui

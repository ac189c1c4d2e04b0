#include "ui/live/live_monitor.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

#include <QElapsedTimer>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QScrollArea>
#include <QSplitter>
#include <QStyle>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "daq/network/net_source.h"
#include "daq/sources/jack_source.h"
#include "daq/sources/replay_source.h"
#include "ui/live/adaptive_test_panel.h"
#include "ui/live/live_analysis_plots.h"
#include "ui/live/live_edc_plot_data.h"
#include "ui/live/live_prediction_job.h"
#include "ui/live/live_source_controls.h"
#include "ui/live/live_source_request.h"
#include "ui/live/live_status_strip.h"
#include "ui/live/live_trace_view.h"
#include "ui/qt_text.h"

namespace oscilab::ui {
namespace {

// Display rate: a frame every 16 ms (≤ 60 Hz). The slower parts run at most one per frame, so
// that no frame does everything at once (the event loop stays responsive).
constexpr int kFrameMs = 16;
enum SlowPart { kStatusPart, kEdcPart, kSlicesPart, kCyclePart, kSlowParts };
// Period of each: the status strip and the event log, the EDC plot, the slices, the loop and
// the spectrum.
constexpr qint64 kPartPeriodMs[kSlowParts] = {100, 250, 250, 250};

}  // namespace

LiveMonitor::LiveMonitor(QWidget* parent)
    : QWidget(parent), clock_(std::make_unique<QElapsedTimer>()) {
  clock_->start();
  prediction_job_ = new LivePredictionJob(this);
  connect(prediction_job_, &LivePredictionJob::finished, this,
          &LiveMonitor::on_prediction_finished);
  frame_timer_ = new QTimer(this);
  frame_timer_->setInterval(kFrameMs);
  connect(frame_timer_, &QTimer::timeout, this, &LiveMonitor::tick);

  // The control panel on the left: the controls over the event log.
  source_controls_ = new LiveSourceControls;
  status_strip_ = new LiveStatusStrip;
  auto* log_group = new QGroupBox(tr("Events"));
  auto* log_layout = new QVBoxLayout(log_group);
  log_layout->setContentsMargins(2, 2, 2, 2);
  log_layout->addWidget(status_strip_->event_log());
  auto* panel = new QWidget;
  auto* panel_layout = new QVBoxLayout(panel);
  panel_layout->setContentsMargins(0, 0, 4, 0);
  panel_layout->addWidget(source_controls_);
  panel_layout->addWidget(log_group, 1);
  panel->setMinimumWidth(270);
  panel->setMaximumWidth(340);
  auto* scroll = new QScrollArea;
  scroll->setWidget(panel);
  scroll->setWidgetResizable(true);
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  // The panel's narrowest width and room for the vertical scroll bar a short screen brings.
  scroll->setMinimumWidth(panel->minimumWidth() + style()->pixelMetric(QStyle::PM_ScrollBarExtent) +
                          4);
  scroll->setFrameShape(QFrame::NoFrame);

  message_label_ = new QLabel;
  message_label_->setObjectName("live_message");
  message_label_->setWordWrap(true);
  message_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  message_label_->setText(tr("Choose a source and press Start."));
  message_label_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);

  // The traces beside the analysis plots.
  trace_view_ = new LiveTraceView;
  analysis_plots_ = new LiveAnalysisPlots;
  analysis_plots_->set_model_label(prediction_job_->model_label());
  auto* plots = new QSplitter(Qt::Horizontal);
  plots->addWidget(trace_view_);
  plots->addWidget(analysis_plots_);
  plots->setStretchFactor(0, 5);
  plots->setStretchFactor(1, 6);
  plots->setChildrenCollapsible(false);

  // The signals (status strip over the plots) and the adaptive test, as tabs.
  auto* signals_page = new QWidget;
  auto* signals_layout = new QVBoxLayout(signals_page);
  signals_layout->setContentsMargins(0, 0, 0, 0);
  signals_layout->addWidget(status_strip_);
  signals_layout->addWidget(plots, 1);
  adaptive_panel_ = new AdaptiveTestPanel;
  views_ = new QTabWidget;
  views_->setDocumentMode(true);
  views_->addTab(signals_page, tr("Signals"));
  views_->addTab(adaptive_panel_, tr("Adaptive test"));

  auto* right = new QVBoxLayout;
  right->setContentsMargins(0, 0, 0, 0);
  right->addWidget(message_label_);
  right->addWidget(views_, 1);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addWidget(scroll);
  layout->addLayout(right, 1);

  connect_controls();
  update_source_controls();
  refresh_status();
  session_settings_ = settings().to_json();
}

LiveMonitor::~LiveMonitor() {
  frame_timer_->stop();
  acquisition_.reset();  // stops the source and joins the threads
}

void LiveMonitor::connect_controls() {
  LiveSourceControls* c = source_controls_;
  connect(c, &LiveSourceControls::settings_edited, this, &LiveMonitor::emit_settings);
  connect(c, &LiveSourceControls::start_requested, this, [this] { start(); });
  connect(c, &LiveSourceControls::stop_requested, this, &LiveMonitor::stop);
  connect(c, &LiveSourceControls::list_ports_requested, this, [this] { list_jack_ports(); });
  connect(c, &LiveSourceControls::excitation_requested, this, &LiveMonitor::set_excitation);
  connect(c, &LiveSourceControls::step_requested, this, &LiveMonitor::step_excitation);
  connect(c, &LiveSourceControls::speed_changed, this, [this](double speed) {
    if (replay_) replay_->set_speed(speed);
  });
  connect(c, &LiveSourceControls::replay_pause_toggled, this, [this](bool paused) {
    if (replay_) replay_->set_paused(paused);
  });
  connect(c, &LiveSourceControls::seek_requested, this, [this](double fraction) {
    if (replay_) replay_->seek(fraction * replay_->duration_s());
  });
  connect(c, &LiveSourceControls::record_requested, this,
          [this](const QString& path) { start_recording(path); });
  connect(c, &LiveSourceControls::stop_recording_requested, this, &LiveMonitor::stop_recording);
  connect(c, &LiveSourceControls::mark_requested, this, &LiveMonitor::mark);
  connect(trace_view_, &LiveTraceView::window_changed, this, &LiveMonitor::emit_settings);
}

// --- settings --------------------------------------------------------------------------------

LiveSettings LiveMonitor::settings() const {
  LiveSettings s = source_controls_->settings();
  s.window_s = trace_view_->window_s();
  return s;
}

void LiveMonitor::set_settings(const LiveSettings& s) {
  set_controls(s);
  emit_settings();
}

void LiveMonitor::set_controls(const LiveSettings& s) {
  applying_settings_ = true;
  source_controls_->set_settings(s);
  trace_view_->set_window_s(s.window_s);
  applying_settings_ = false;
  update_source_controls();
}

void LiveMonitor::apply_settings(const nlohmann::json& json) {
  session_settings_ = json;
  try {
    set_controls(LiveSettings::from_json(json));
  } catch (const std::exception& error) {
    show_message(tr("Live settings not restored: %1").arg(error.what()), true);
  }
}

void LiveMonitor::emit_settings() {
  if (applying_settings_) return;
  session_settings_ = settings().to_json();
  Q_EMIT settings_changed(session_settings_);
}

void LiveMonitor::set_rig_schedule(std::vector<daq::ExcitationStep> schedule) {
  source_controls_->set_rig_schedule(std::move(schedule));
}

void LiveMonitor::set_rig_duration(std::optional<double> duration_s) {
  source_controls_->set_rig_duration(duration_s);
}

void LiveMonitor::update_source_controls() {
  source_controls_->show_state(acquisition_ != nullptr && running(), rig_ != nullptr,
                               replay_ != nullptr);
}

void LiveMonitor::show_message(const QString& text, bool error) {
  message_label_->setText(text);
  message_label_->setStyleSheet(error ? QStringLiteral("color: rgb(180,30,20)") : QString());
  Q_EMIT message_shown(text);
}

QString LiveMonitor::message() const { return message_label_->text(); }

// --- running ---------------------------------------------------------------------------------

bool LiveMonitor::start() {
  stop();
  const LiveSettings s = settings();
  const std::vector<daq::ExcitationStep>& schedule = source_controls_->rig_schedule();
  std::unique_ptr<daq::SampleSource> source;
  daq::RigSource* rig = nullptr;
  daq::ReplaySource* replay = nullptr;
  daq::NetSource* net = nullptr;
  daq::JackSource* jack = nullptr;
  try {
    // One factory for the CLI and the app (daq/live/source_factory.h).
    const LiveSourceRequest request =
        live_source_request(s, schedule, source_controls_->rig_duration_s());
    source = daq::make_source(request.spec, request.options);
    rig = dynamic_cast<daq::RigSource*>(source.get());
    replay = dynamic_cast<daq::ReplaySource*>(source.get());
    net = dynamic_cast<daq::NetSource*>(source.get());
    jack = dynamic_cast<daq::JackSource*>(source.get());
    if (rig != nullptr && schedule.empty() && s.rig_f0_n > 0) {
      rig->set_excitation(s.rig_f0_n, s.rig_frequency_hz);
    }
    daq::AcquisitionOptions options;
    options.alarms = s.alarms;
    auto acquisition = std::make_unique<daq::Acquisition>(std::move(source), options);
    acquisition->start();
    acquisition_ = std::move(acquisition);
  } catch (const std::exception& error) {
    show_message(tr("Cannot start: %1").arg(error.what()), true);
    update_source_controls();
    return false;
  }
  rig_ = rig;
  replay_ = replay;
  net_ = net;
  jack_ = jack;
  layout_ = acquisition_->source().layout();  // rig, replay: known now; network: once sent

  // A fresh view of the new stream.
  trace_view_->show_stream(acquisition_.get(), layout_);
  source_controls_->reset_replay_pause();
  status_strip_->reset();
  analysis_plots_->reset(frequency_hz());
  std::fill(std::begin(last_part_ms_), std::end(last_part_ms_), -1000);

  show_message(net_ ? tr("Listening on 127.0.0.1:%1 for a sender.").arg(net_->port())
                    : tr("Started: %1.").arg(qtext(acquisition_->source().describe())),
               false);
  update_source_controls();
  start_prediction(frequency_hz());
  frame_timer_->start();
  Q_EMIT started();
  return true;
}

void LiveMonitor::stop() {
  if (!acquisition_) return;
  const bool was_running = running();
  frame_timer_->stop();
  acquisition_->stop();
  refresh();
  check_recording_closed();
  update_source_controls();
  if (was_running) {
    show_message(
        tr("Stopped at %1 s of stream.").arg(acquisition_->status().stream_time_s, 0, 'f', 1),
        false);
    Q_EMIT stopped();
  }
}

bool LiveMonitor::running() const {
  if (!acquisition_) return false;
  const daq::AcquisitionStatus s = acquisition_->status();
  return s.running && !s.finished;
}

bool LiveMonitor::start_recording(const QString& path) {
  if (!acquisition_ || !running()) {
    show_message(tr("Start a source before recording."), true);
    return false;
  }
  try {
    acquisition_->start_recording(path.toStdString());
  } catch (const std::exception& error) {
    show_message(tr("Cannot record: %1").arg(error.what()), true);
    return false;
  }
  show_message(tr("Recording to %1").arg(path), false);
  recording_path_ = path;
  source_controls_->show_recording(true);
  return true;
}

void LiveMonitor::stop_recording() {
  if (!acquisition_) return;
  acquisition_->stop_recording();
  source_controls_->show_recording(false);
}

void LiveMonitor::mark(const QString& text) {
  if (!acquisition_ || !running()) {
    show_message(tr("Nothing to mark: no source is running."), true);
    return;
  }
  acquisition_->mark(text.toStdString());
}

void LiveMonitor::set_excitation(double f0_n, double frequency_hz) {
  if (!rig_ || !running()) {
    show_message(tr("Start the virtual rig first."), true);
    return;
  }
  try {
    rig_->set_excitation(f0_n, frequency_hz);
  } catch (const std::exception& error) {
    show_message(tr("Cannot set the excitation: %1").arg(error.what()), true);
    return;
  }
  source_controls_->show_excitation_fields(f0_n, frequency_hz);
  emit_settings();
  show_message(tr("Excitation set: f\u2080 = %1 N at %2 Hz.").arg(f0_n).arg(frequency_hz), false);
}

void LiveMonitor::step_excitation() {
  if (!rig_) {
    show_message(tr("Start the virtual rig first."), true);
    return;
  }
  const daq::ExcitationStep now = rig_->excitation();
  set_excitation(now.f0_n + source_controls_->step_n(), now.frequency_hz);
}

void LiveMonitor::set_view_paused(bool paused) { trace_view_->set_paused(paused); }

bool LiveMonitor::view_paused() const { return trace_view_->paused(); }

void LiveMonitor::scroll_view_to(double end_s) { trace_view_->scroll_to(end_s); }

TimeWindow LiveMonitor::view_window() const { return trace_view_->view_window(); }

long LiveMonitor::frames_drawn() const { return trace_view_->frames_drawn(); }

double LiveMonitor::frequency_hz() const {
  if (rig_) return rig_->excitation().frequency_hz;
  if (acquisition_) {
    if (layout_ && layout_->excitation && layout_->excitation->frequency_hz) {
      return *layout_->excitation->frequency_hz;
    }
    return 0.0;
  }
  return source_controls_->frequency_hz();
}

bool LiveMonitor::list_jack_ports() {
  try {
    const std::vector<std::string> ports =
        daq::JackSource::capture_ports(source_controls_->jack_server().toStdString());
    source_controls_->set_jack_ports(ports);
    show_message(
        tr("%n capture port(s) on the JACK server.", nullptr, static_cast<int>(ports.size())),
        false);
    return true;
  } catch (const std::exception& error) {
    show_message(tr("Cannot list JACK ports: %1").arg(error.what()), true);
    return false;
  }
}

// --- drawing ---------------------------------------------------------------------------------

void LiveMonitor::check_recording_closed() {
  if (recording_path_.isEmpty() || !acquisition_ || acquisition_->status().recording) return;
  const QString path = recording_path_;
  recording_path_.clear();
  Q_EMIT recording_finished(path);
}

void LiveMonitor::tick() {
  if (!acquisition_) return;
  check_recording_closed();
  refresh_traces();
  // At most one slower part per frame: the most overdue one.
  const qint64 now = clock_->elapsed();
  int due = -1;
  qint64 most_overdue = 0;
  for (int part = 0; part < kSlowParts; ++part) {
    const qint64 overdue = now - last_part_ms_[part] - kPartPeriodMs[part];
    if (overdue >= most_overdue) due = part, most_overdue = overdue;
  }
  if (due >= 0) last_part_ms_[due] = now;
  switch (due) {
    case kStatusPart:
      refresh_status();
      break;
    case kEdcPart:
      refresh_edc();
      break;
    case kSlicesPart:
      refresh_slices();
      break;
    case kCyclePart:
      refresh_cycle();
      break;
    default:
      break;
  }
  if (acquisition_->finished()) {
    // The source ended and all it sent is shown: draw the last of it and rest.
    frame_timer_->stop();
    refresh();
    update_source_controls();
    show_message(tr("The source ended at %1 s of stream (%2).")
                     .arg(acquisition_->status().stream_time_s, 0, 'f', 1)
                     .arg(qtext(acquisition_->source().describe())),
                 false);
  }
}

void LiveMonitor::refresh() {
  if (!acquisition_) return;
  refresh_traces();
  refresh_status();
  refresh_analysis();
}

void LiveMonitor::refresh_traces() {
  if (!acquisition_) return;
  if (!layout_ && acquisition_->status().layout_known) {  // a network sender's layout arrived
    layout_ = acquisition_->layout();
    trace_view_->set_layout(layout_);
  }
  trace_view_->refresh();
}

void LiveMonitor::refresh_status() {
  if (jack_ != nullptr && running()) source_controls_->show_jack_peaks(jack_->peaks());
  if (!acquisition_) {
    status_strip_->show_idle();
    return;
  }
  const daq::AcquisitionStatus status = acquisition_->status();
  status_strip_->update(*acquisition_, status);
  source_controls_->show_recording(status.recording);
  if (rig_) source_controls_->show_rig_excitation(rig_->excitation());
  if (replay_) source_controls_->show_replay_position(replay_->position_s(), replay_->duration_s());
}

void LiveMonitor::refresh_analysis() {
  refresh_edc();
  refresh_slices();
  refresh_cycle();
}

void LiveMonitor::refresh_slices() {
  if (acquisition_) analysis_plots_->refresh_slices(*acquisition_, frequency_hz());
}

void LiveMonitor::refresh_cycle() {
  if (acquisition_) analysis_plots_->refresh_cycle(*acquisition_, frequency_hz());
}

void LiveMonitor::refresh_edc() {
  if (!acquisition_) return;
  const std::vector<analysis::LevelResult> levels = acquisition_->levels();
  const double nu = frequency_hz();
  if (prediction_job_->needed(nu, edc_plot_data(levels, std::nullopt).max_f0_n)) {
    start_prediction(nu);  // a new ν, or levels past the prediction's
  }
  analysis_plots_->show_edc(levels, acquisition_->current_level());
}

// --- the model's prediction ------------------------------------------------------------------

void LiveMonitor::set_prediction_model(std::shared_ptr<const analysis::Model> model,
                                       const QString& label) {
  if (!model) return;
  prediction_job_->set_model(std::move(model), label);
  analysis_plots_->set_model_label(label);
  if (acquisition_) start_prediction(frequency_hz());
}

void LiveMonitor::start_prediction(double frequency_hz) {
  const double max_f0 =
      acquisition_ ? edc_plot_data(acquisition_->levels(), std::nullopt).max_f0_n : 0.0;
  prediction_job_->start(frequency_hz, max_f0);
}

void LiveMonitor::on_prediction_finished() {
  analysis_plots_->show_model_edc(prediction_job_->well(0), prediction_job_->well(1));
  if (acquisition_) {
    refresh_edc();
  } else {
    analysis_plots_->edc_plot()->replot();
  }
  Q_EMIT prediction_finished(prediction_job_->message());
  if (prediction_job_->again()) start_prediction(frequency_hz());
}

}  // namespace oscilab::ui

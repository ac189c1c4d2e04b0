#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QString>
#include <QWidget>

#include <nlohmann/json.hpp>

#include "analysis/model/model.h"
#include "analysis/rfs/streaming_slices.h"
#include "daq/live/acquisition.h"
#include "daq/live/rig_source.h"
#include "ui/display_units.h"
#include "ui/live_axis_following.h"
#include "ui/live_faults.h"
#include "ui/live_settings.h"
#include "ui/live_timeline.h"
#include "ui/throughput_meter.h"

class QAction;
class QCheckBox;
class QComboBox;
class QCPAxisRect;
class QCPErrorBars;
class QCPGraph;
class QCPItemText;
class QCustomPlot;
class QDoubleSpinBox;
class QElapsedTimer;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QScrollBar;
class QSlider;
class QSpinBox;
class QTableWidget;
class QTimer;

namespace oscilab::daq {
class JackSource;
class NetSource;
class ReplaySource;
}  // namespace oscilab::daq

namespace oscilab::ui {

class BackgroundJob;

/// The live monitor: one live source (the virtual rig, a recording replayed, or a
/// network stream received on 127.0.0.1) through daq::Acquisition, shown as it arrives:
///
/// - controls: source, Start/Stop; the rig's f₀ and ν (Set, Step +ΔN); the replay's speed, pause
///   and position; Record… / Stop recording (WAV, crash-safe); Mark; alarm limits on |z|, |b|
///   (integration drift) and |f|;
/// - a status strip (rate, stream time, samples, fault counters that turn amber and red as they
///   rise, queue, recording, cycles, latency, alarms) and the event log;
/// - traces of b̈, b, y, z and f over a window that follows the stream, or paused (the
///   acquisition goes on) and scrolled back over the last 10 minutes;
/// - the restoring-force surface growing live (stiffness and damping slices, §3.1–3.2) and the
///   force–displacement loop of the current cycle (Fig. 9), coloured by well;
/// - the EDC against f₀ of both wells, level by level with ±3σ bars (Fig. 10), under the paper's
///   model (Tables 1 and 3) by harmonic balance, computed on a worker thread;
/// - the spectrum of z with the excitation's harmonics, and a warning when the current level is
///   not period-1 or crosses wells.
///
/// The acquisition runs on its own threads; the monitor polls it at display rate (a 60 Hz
/// timer: traces every frame, the rest every 100–250 ms) and never waits on the UI thread but
/// for Start and Stop (which join threads, ≤ ~100 ms). Errors (a file that cannot be read, a
/// busy port, a bad recording path) are shown in the message line and by message_shown(),
/// never thrown. Used from the UI thread only.
class LiveMonitor : public QWidget {
  Q_OBJECT

 public:
  explicit LiveMonitor(QWidget* parent = nullptr);
  ~LiveMonitor() override;

  /// Starts the source the controls describe (stopping one that runs). Returns false and shows
  /// why when it cannot start (unreadable file, busy port, bad settings).
  bool start();
  /// Stops the source and the acquisition (joins their threads); what was shown stays.
  void stop();
  bool running() const;

  /// The acquisition shown (null before the first start); its sources, when of that kind.
  daq::Acquisition* acquisition() const { return acquisition_.get(); }
  daq::RigSource* rig() const { return rig_; }
  daq::ReplaySource* replay() const { return replay_; }
  daq::NetSource* net() const { return net_; }
  daq::JackSource* jack() const { return jack_; }

  /// Fills the JACK port choices with the capture ports of the server named in the controls;
  /// false and a message when no server answers.
  bool list_jack_ports();
  /// The level meters of a JACK source: peak of the base (0) and mass (1) channel since the last
  /// refresh, in % of the interface's full scale.
  QProgressBar* jack_meter(int channel) const { return jack_meters_[channel == 0 ? 0 : 1]; }
  QComboBox* jack_port_box(int channel) const { return jack_port_boxes_[channel == 0 ? 0 : 1]; }

  /// The settings of the controls (MainWindow stores them in the session).
  LiveSettings settings() const;
  /// Sets the controls; takes effect at the next start for what a running source cannot change.
  void set_settings(const LiveSettings& settings);
  /// Sets the controls from a session's "live" JSON (without settings_changed: the session
  /// keeps its copy verbatim); a bad value is shown, nothing changes.
  void apply_settings(const nlohmann::json& settings);
  /// The model whose EDC is drawn over the measured points (default: the paper's, Tables 1 and
  /// 3); `label` names it in the legend. The fit panel hands over each fitted model.
  void set_prediction_model(std::shared_ptr<const analysis::Model> model, const QString& label);
  /// An unattended stepped sine for the rig's next start (empty: the rig rests until told).
  void set_rig_schedule(std::vector<daq::ExcitationStep> schedule);
  /// The rig runs for this long of stream time, then ends (none: until stopped).
  void set_rig_duration(std::optional<double> duration_s) { rig_duration_s_ = duration_s; }

  /// Records the stream to `path` (.wav, .w64, .rf64) from the next block on; false and a
  /// message when it cannot.
  bool start_recording(const QString& path);
  void stop_recording();
  /// An operator's mark in the event log at the current stream time.
  void mark(const QString& text);
  /// The rig: ramp to f0 at ν from the next block on / step f0 by +ΔN.
  void set_excitation(double f0_n, double frequency_hz);
  void step_excitation();

  /// Pauses the traces (the acquisition goes on) or follows the stream again.
  void set_view_paused(bool paused);
  bool view_paused() const { return !timeline_.following(); }
  /// Pauses the view and shows the window ending at `end_s` (stream time).
  void scroll_view_to(double end_s);
  /// The window of the traces, in stream time.
  TimeWindow view_window() const { return timeline_.view(); }

  /// Polls the acquisition and redraws everything now (the timer does it at display rate).
  void refresh();
  /// Trace-plot frames drawn since construction (QCustomPlot replots).
  long frames_drawn() const { return frames_; }
  /// The message line: the last error or notice.
  QString message() const;

  QCustomPlot* trace_plot() const { return trace_plot_; }
  QCustomPlot* edc_plot() const { return edc_plot_; }
  QCustomPlot* stiffness_plot() const { return stiffness_plot_; }
  QCustomPlot* damping_plot() const { return damping_plot_; }
  QCustomPlot* loop_plot() const { return loop_plot_; }
  QCustomPlot* spectrum_plot() const { return spectrum_plot_; }
  /// EDC graphs: measured positive / negative / other wells, the level being filled, and the
  /// model's prediction per well (empty until computed).
  QCPGraph* edc_graph(const std::string& well) const;
  QCPGraph* current_level_graph() const { return current_graph_; }
  QCPGraph* model_graph(bool positive_well) const { return model_graphs_[positive_well ? 0 : 1]; }
  /// The status strip's value label for a key of status_fields ("samples", "gaps", ...).
  QLabel* status_label(const QString& key) const;
  QLabel* warning_label() const { return warning_label_; }
  QTableWidget* event_log() const { return event_log_; }
  QComboBox* source_box() const { return source_box_; }
  QComboBox* speed_box() const { return speed_box_; }
  QDoubleSpinBox* f0_box() const { return f0_box_; }
  QDoubleSpinBox* frequency_box() const { return frequency_box_; }
  QDoubleSpinBox* window_box() const { return window_box_; }
  QLineEdit* replay_path_edit() const { return replay_path_edit_; }
  QPushButton* start_button() const { return start_button_; }
  QPushButton* stop_button() const { return stop_button_; }
  QPushButton* record_button() const { return record_button_; }
  QPushButton* stop_recording_button() const { return stop_recording_button_; }
  QPushButton* pause_view_button() const { return pause_view_button_; }
  QScrollBar* scroll_bar() const { return scroll_bar_; }

 Q_SIGNALS:
  /// A control that the session keeps changed; `settings` is LiveSettings::to_json().
  void settings_changed(const nlohmann::json& settings);
  /// An error or notice was shown in the message line.
  void message_shown(const QString& message);
  void started();
  void stopped();
  /// A recording started here was closed (Stop recording, or the source stopped or ended): the
  /// file is complete and can be reviewed and fitted.
  void recording_finished(const QString& path);
  /// A model prediction was drawn (or failed: `message` says why).
  void prediction_finished(const QString& message);

 private:
  struct Prediction;
  void build_controls(QWidget* panel);
  void build_plots();
  void set_controls(const LiveSettings& settings);  // without settings_changed
  void show_message(const QString& text, bool error);
  void emit_settings();
  void update_source_controls();
  void tick();
  void check_recording_closed();
  void refresh_traces();
  void refresh_status();
  void refresh_analysis();  // the three below
  void refresh_slices();
  void refresh_cycle();
  void refresh_edc();
  void start_prediction(double frequency_hz);
  void on_prediction_finished(bool cancelled);
  void sync_scroll_bar();
  double frequency_hz() const;

  std::unique_ptr<daq::Acquisition> acquisition_;
  daq::RigSource* rig_ = nullptr;
  daq::ReplaySource* replay_ = nullptr;
  daq::NetSource* net_ = nullptr;
  daq::JackSource* jack_ = nullptr;
  std::optional<daq::Sidecar> layout_;  // of the stream shown, once known
  std::vector<daq::ExcitationStep> rig_schedule_;
  std::optional<double> rig_duration_s_;
  bool applying_settings_ = false;

  LiveTimeline timeline_;
  FaultCounts event_faults_;
  FaultTracker fault_tracker_;
  ThroughputMeter throughput_;
  analysis::StreamingSlices rfs_;
  std::size_t events_seen_ = 0;
  std::size_t levels_shown_ = static_cast<std::size_t>(-1);
  std::optional<analysis::LevelResult> current_shown_;
  daq::TraceHistory traces_, raw_;  // reused buffers
  std::vector<std::optional<DisplayUnit>> trace_units_;
  std::vector<std::optional<AxisRange>> trace_ranges_;
  std::unique_ptr<QElapsedTimer> clock_;
  qint64 last_part_ms_[4] = {-1000, -1000, -1000, -1000};  // when each slow part last ran
  long frames_ = 0;

  BackgroundJob* prediction_job_ = nullptr;
  std::shared_ptr<Prediction> prediction_;                   // written by the worker
  std::shared_ptr<const analysis::Model> prediction_model_;  // drawn over the measured EDC
  QString prediction_label_;
  QString recording_path_;               // of the recording running, until recording_finished
  double predicted_frequency_hz_ = 0.0;  // of the prediction drawn or running
  double predicted_top_n_ = 0.0;         // its largest level
  bool prediction_again_ = false;

  QTimer* frame_timer_ = nullptr;
  QLabel* message_label_ = nullptr;
  QLabel* warning_label_ = nullptr;
  std::vector<std::pair<std::string, QLabel*>> status_labels_;
  QTableWidget* event_log_ = nullptr;

  QLineEdit* jack_server_edit_ = nullptr;
  QLineEdit* jack_calibration_edit_ = nullptr;
  QComboBox* jack_port_boxes_[2] = {nullptr, nullptr};
  QPushButton* jack_list_button_ = nullptr;
  QProgressBar* jack_meters_[2] = {nullptr, nullptr};
  QComboBox* source_box_ = nullptr;
  QLineEdit* replay_path_edit_ = nullptr;
  QPushButton* browse_button_ = nullptr;
  QCheckBox* loop_box_ = nullptr;
  QSpinBox* port_box_ = nullptr;
  QPushButton* start_button_ = nullptr;
  QPushButton* stop_button_ = nullptr;
  QWidget* rig_group_ = nullptr;
  QWidget* replay_group_ = nullptr;
  QLabel* rig_now_label_ = nullptr;
  QComboBox* well_box_ = nullptr;
  QDoubleSpinBox* f0_box_ = nullptr;
  QDoubleSpinBox* frequency_box_ = nullptr;
  QDoubleSpinBox* step_box_ = nullptr;
  QPushButton* set_button_ = nullptr;
  QPushButton* step_button_ = nullptr;
  QComboBox* speed_box_ = nullptr;
  QPushButton* replay_pause_button_ = nullptr;
  QSlider* seek_slider_ = nullptr;
  QLabel* seek_label_ = nullptr;
  QPushButton* record_button_ = nullptr;
  QPushButton* stop_recording_button_ = nullptr;
  QLineEdit* mark_edit_ = nullptr;
  QPushButton* mark_button_ = nullptr;
  QDoubleSpinBox* alarm_z_box_ = nullptr;
  QDoubleSpinBox* alarm_b_box_ = nullptr;
  QDoubleSpinBox* alarm_f_box_ = nullptr;
  QDoubleSpinBox* window_box_ = nullptr;
  QPushButton* pause_view_button_ = nullptr;
  QScrollBar* scroll_bar_ = nullptr;

  QCustomPlot* trace_plot_ = nullptr;
  std::vector<QCPAxisRect*> trace_rects_;
  std::vector<QCPGraph*> trace_graphs_;
  std::vector<QCPItemText*> trace_names_;
  QCustomPlot* edc_plot_ = nullptr;
  QCPGraph* edc_graphs_[3] = {nullptr, nullptr, nullptr};  // positive, negative, other
  QCPGraph* current_graph_ = nullptr;
  QCPErrorBars* edc_bars_[4] = {nullptr, nullptr, nullptr, nullptr};  // wells, then current
  QCPGraph* model_graphs_[2] = {nullptr, nullptr};
  QCustomPlot* stiffness_plot_ = nullptr;
  QCustomPlot* damping_plot_ = nullptr;
  QCustomPlot* loop_plot_ = nullptr;
  QCustomPlot* spectrum_plot_ = nullptr;
};

}  // namespace oscilab::ui

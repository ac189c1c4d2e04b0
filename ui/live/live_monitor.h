#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <QString>
#include <QWidget>

#include <nlohmann/json.hpp>

#include "analysis/model/model.h"
#include "daq/live/acquisition.h"
#include "daq/sources/rig_source.h"
#include "ui/live/live_settings.h"
#include "ui/time_window.h"

class QElapsedTimer;
class QLabel;
class QTabWidget;
class QTimer;

namespace oscilab::daq {
class JackSource;
class NetSource;
class ReplaySource;
}  // namespace oscilab::daq

namespace oscilab::ui {

class AdaptiveTestPanel;
class LiveAnalysisPlots;
class LivePredictionJob;
class LiveSourceControls;
class LiveStatusStrip;
class LiveTraceView;

/// The live monitor: one live source (the virtual rig, a recording replayed, a network stream
/// received on 127.0.0.1, or a JACK sound card) through daq::Acquisition, shown as it arrives.
/// It owns the acquisition and coordinates the parts that show it:
///
/// - LiveSourceControls: source, Start/Stop; the rig's f₀ and ν (Set, Step +ΔN); the replay's
///   speed, pause and position; Record… / Stop recording (WAV, crash-safe); Mark; alarm limits
///   on |z|, |b| (integration drift) and |f|;
/// - LiveStatusStrip: rate, stream time, samples, fault counters that turn amber and red as
///   they rise, queue, recording, cycles, latency, alarms; the level being filled with a warning
///   when it is not period-1 or crosses wells; and the event log;
/// - LiveTraceView: traces of b̈, b, y, z and f over a window that follows the stream, or paused
///   (the acquisition goes on) and scrolled back over the last 10 minutes;
/// - LiveAnalysisPlots: the restoring-force surface growing live (stiffness and damping slices,
///   §3.1–3.2), the force–displacement loop of the current cycle (Fig. 9), the EDC against f₀ of
///   both wells, level by level with ±3σ bars (Fig. 10), and the spectrum of z;
/// - LivePredictionJob: the model's EDC (default: the paper's, Tables 1 and 3) by harmonic
///   balance on a worker thread, drawn under the measured levels;
/// - AdaptiveTestPanel (the "Adaptive test" tab beside the signals): a stepped-sine test on a
///   virtual rig of its own that chooses its levels, its model weights, proposals and verdict.
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
  AdaptiveTestPanel* adaptive_test() const { return adaptive_panel_; }
  /// The tabs of the right column: "Signals" (traces and analysis plots), "Adaptive test".
  QTabWidget* views() const { return views_; }

  /// Fills the JACK port choices with the capture ports of the server named in the controls;
  /// false and a message when no server answers.
  bool list_jack_ports();

  /// The settings of the controls.
  LiveSettings settings() const;
  /// The session's "live" part: the JSON the last session restored, verbatim (keys of other
  /// versions kept), or the controls' settings once they changed.
  nlohmann::json session_settings() const { return session_settings_; }
  /// Sets the controls; takes effect at the next start for what a running source cannot change.
  void set_settings(const LiveSettings& settings);
  /// Sets the controls from a session's "live" JSON, kept verbatim as session_settings()
  /// (without settings_changed); a bad value is shown, the controls do not change.
  void apply_settings(const nlohmann::json& settings);
  /// The model whose EDC is drawn over the measured points (default: the paper's, Tables 1 and
  /// 3); `label` names it in the legend. The fit panel hands over each fitted model.
  void set_prediction_model(std::shared_ptr<const analysis::Model> model, const QString& label);
  /// An unattended stepped sine for the rig's next start (empty: the rig rests until told).
  void set_rig_schedule(std::vector<daq::ExcitationStep> schedule);
  /// The rig runs for this long of stream time, then ends (none: until stopped).
  void set_rig_duration(std::optional<double> duration_s);

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
  bool view_paused() const;
  /// Pauses the view and shows the window ending at `end_s` (stream time).
  void scroll_view_to(double end_s);
  /// The window of the traces, in stream time.
  TimeWindow view_window() const;

  /// Polls the acquisition and redraws everything now (the timer does it at display rate).
  void refresh();
  /// Trace-plot frames drawn since construction (QCustomPlot replots).
  long frames_drawn() const;
  /// The message line: the last error or notice.
  QString message() const;

  /// The parts (each widget keeps its objectName for QObject::findChild).
  LiveSourceControls* source_controls() const { return source_controls_; }
  LiveStatusStrip* status_strip() const { return status_strip_; }
  LiveTraceView* trace_view() const { return trace_view_; }
  LiveAnalysisPlots* analysis_plots() const { return analysis_plots_; }
  LivePredictionJob* prediction_job() const { return prediction_job_; }

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
  void connect_controls();
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
  void on_prediction_finished();
  double frequency_hz() const;

  std::unique_ptr<daq::Acquisition> acquisition_;
  daq::RigSource* rig_ = nullptr;
  daq::ReplaySource* replay_ = nullptr;
  daq::NetSource* net_ = nullptr;
  daq::JackSource* jack_ = nullptr;
  std::optional<daq::Sidecar> layout_;  // of the stream shown, once known
  bool applying_settings_ = false;
  nlohmann::json session_settings_ = nlohmann::json::object();
  QString recording_path_;  // of the recording running, until recording_finished

  std::unique_ptr<QElapsedTimer> clock_;
  qint64 last_part_ms_[4] = {-1000, -1000, -1000, -1000};  // when each slow part last ran
  QTimer* frame_timer_ = nullptr;

  LiveSourceControls* source_controls_ = nullptr;
  LiveStatusStrip* status_strip_ = nullptr;
  LiveTraceView* trace_view_ = nullptr;
  LiveAnalysisPlots* analysis_plots_ = nullptr;
  LivePredictionJob* prediction_job_ = nullptr;
  AdaptiveTestPanel* adaptive_panel_ = nullptr;
  QTabWidget* views_ = nullptr;
  QLabel* message_label_ = nullptr;
};

}  // namespace oscilab::ui

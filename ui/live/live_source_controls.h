#pragma once

#include <optional>
#include <string>
#include <vector>

#include <QString>
#include <QWidget>

#include "daq/sources/rig_source.h"
#include "ui/live/live_settings.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QGroupBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QSlider;
class QSpinBox;

namespace oscilab::ui {

/// The live monitor's control panel: the source (the virtual rig, a recording replayed, a
/// network stream on 127.0.0.1, or a JACK sound card) with its fields and Start/Stop; the rig's
/// f₀ and ν (Set, Step +ΔN) and its unattended stepped sine; the replay's pause and position;
/// Record… / Stop recording and Mark; and the alarm limits. It holds the settings the session
/// keeps (but the traces' window) and asks for actions by signals; the monitor acts and tells
/// it what runs (show_state). Used from the UI thread only.
class LiveSourceControls : public QWidget {
  Q_OBJECT

 public:
  explicit LiveSourceControls(QWidget* parent = nullptr);

  /// The settings of the controls; window_s keeps its default (the trace view has it).
  LiveSettings settings() const;
  /// Sets the controls (each change emits settings_edited: the caller decides what to keep).
  void set_settings(const LiveSettings& settings);

  /// An unattended stepped sine for the rig's next start (empty: the rig rests until told).
  void set_rig_schedule(std::vector<daq::ExcitationStep> schedule);
  const std::vector<daq::ExcitationStep>& rig_schedule() const { return rig_schedule_; }
  /// The rig runs for this long of stream time, then ends (none: until stopped).
  void set_rig_duration(std::optional<double> duration_s) { rig_duration_s_ = duration_s; }
  std::optional<double> rig_duration_s() const { return rig_duration_s_; }

  /// What runs: enables the controls that apply (a source runs: `live`; its kind: a rig or a
  /// replay, kept after it stopped).
  void show_state(bool live, bool rig, bool replay);
  /// The excitation the rig runs now.
  void show_rig_excitation(const daq::ExcitationStep& now);
  /// Sets the f₀ and ν fields without settings_edited.
  void show_excitation_fields(double f0_n, double frequency_hz);
  /// The replay's position in its file.
  void show_replay_position(double position_s, double duration_s);
  /// A new replay starts unpaused.
  void reset_replay_pause();
  /// Whether a recording runs (Stop recording applies).
  void show_recording(bool recording);
  /// The JACK level meters: the peak of each channel in % of full scale.
  void show_jack_peaks(const std::vector<double>& peaks_percent);
  /// The capture ports a JACK server listed, offered in both port boxes (the choice kept).
  void set_jack_ports(const std::vector<std::string>& ports);

  double f0_n() const;
  double frequency_hz() const;  // the ν field
  double step_n() const;        // ΔN of Step +ΔN
  QString jack_server() const;

  /// The level meter (0: base, 1: mass) and the capture port box of a JACK channel.
  QProgressBar* jack_meter(int channel) const { return jack_meters_[channel == 0 ? 0 : 1]; }
  QComboBox* jack_port_box(int channel) const { return jack_port_boxes_[channel == 0 ? 0 : 1]; }

 Q_SIGNALS:
  /// A field the session keeps changed.
  void settings_edited();
  void start_requested();
  void stop_requested();
  void list_ports_requested();
  /// Set: ramp the rig to f₀ at ν.
  void excitation_requested(double f0_n, double frequency_hz);
  /// Step +ΔN.
  void step_requested();
  /// The replay's speed (× real time, 0: as fast as possible), pause, and seek (fraction of
  /// the file).
  void speed_changed(double speed);
  void replay_pause_toggled(bool paused);
  void seek_requested(double fraction);
  void record_requested(const QString& path);
  void stop_recording_requested();
  void mark_requested(const QString& text);

 private:
  QGroupBox* make_source_group();
  QGroupBox* make_rig_group();
  QGroupBox* make_replay_group();
  QGroupBox* make_record_group();
  QGroupBox* make_alarm_group();
  void update_enabled();

  std::vector<daq::ExcitationStep> rig_schedule_;
  std::optional<double> rig_duration_s_;
  bool live_ = false, rig_ = false, replay_ = false;  // as show_state was told

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
};

}  // namespace oscilab::ui

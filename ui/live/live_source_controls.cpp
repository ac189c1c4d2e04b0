#include "ui/live/live_source_controls.h"
#include "ui/qt_text.h"

#include <algorithm>
#include <cmath>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QVBoxLayout>

namespace oscilab::ui {
namespace {}  // namespace

LiveSourceControls::LiveSourceControls(QWidget* parent) : QWidget(parent) {
  setObjectName("live_source_controls");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);

  layout->addWidget(make_source_group());
  layout->addWidget(make_rig_group());
  layout->addWidget(make_replay_group());
  layout->addWidget(make_record_group());
  layout->addWidget(make_alarm_group());
  update_enabled();
}

// The source: its kind and each kind's settings (a file to replay, a port to listen on, JACK's
// server, ports and calibration), the speed, Start and Stop.
QGroupBox* LiveSourceControls::make_source_group() {
  auto* source_group = new QGroupBox(tr("Source"));
  source_box_ = new QComboBox;
  source_box_->setObjectName("source");
  source_box_->addItem(tr("Virtual rig (paper model)"));
  source_box_->addItem(tr("Replay a file\u2026"));
  source_box_->addItem(tr("Network: listen on 127.0.0.1"));
  source_box_->addItem(tr("JACK (sound card)"));
  replay_path_edit_ = new QLineEdit;
  replay_path_edit_->setObjectName("replay_path");
  replay_path_edit_->setPlaceholderText(tr("recording to replay"));
  browse_button_ = new QPushButton(tr("\u2026"));
  browse_button_->setToolTip(tr("Choose the recording to replay"));
  browse_button_->setMaximumWidth(32);
  connect(browse_button_, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Replay a recording"), QFileInfo(replay_path_edit_->text()).path(),
        tr("Recordings (*.wav *.flac *.w64 *.rf64 *.aiff *.aif *.caf *.csv);;All files (*)"));
    if (!path.isEmpty()) replay_path_edit_->setText(path);
  });
  auto* path_row = new QHBoxLayout;
  path_row->addWidget(replay_path_edit_, 1);
  path_row->addWidget(browse_button_);
  loop_box_ = new QCheckBox(tr("loop"));
  loop_box_->setToolTip(tr("Replay: start again at the end of the file"));
  port_box_ = new QSpinBox;
  port_box_->setObjectName("port");
  port_box_->setRange(0, 65535);
  port_box_->setValue(5025);
  port_box_->setSpecialValueText(tr("any free port"));
  port_box_->setToolTip(tr("Network: the TCP port to listen on (127.0.0.1 only)"));
  // JACK: the server, a capture port per channel (listed from the server, or typed), the
  // calibration sidecar, and a level meter per channel.
  jack_server_edit_ = new QLineEdit;
  jack_server_edit_->setObjectName("jack_server");
  jack_server_edit_->setPlaceholderText(tr("default server"));
  jack_server_edit_->setToolTip(tr("JACK: the server's name (empty: the default server)"));
  jack_list_button_ = new QPushButton(tr("List ports"));
  jack_list_button_->setToolTip(tr("JACK: list the server's capture ports"));
  connect(jack_list_button_, &QPushButton::clicked, this,
          &LiveSourceControls::list_ports_requested);
  auto* jack_server_row = new QHBoxLayout;
  jack_server_row->addWidget(jack_server_edit_, 1);
  jack_server_row->addWidget(jack_list_button_);
  const char* jack_roles[2] = {"jack_base_port", "jack_mass_port"};
  for (int c = 0; c < 2; ++c) {
    jack_port_boxes_[c] = new QComboBox;
    jack_port_boxes_[c]->setObjectName(jack_roles[c]);
    jack_port_boxes_[c]->setEditable(true);
    jack_meters_[c] = new QProgressBar;
    jack_meters_[c]->setRange(0, 100);
    jack_meters_[c]->setValue(0);
    jack_meters_[c]->setFormat(tr("%p % of full scale"));
    jack_meters_[c]->setToolTip(tr("Peak since the last refresh, in % of the input's full scale"));
  }
  jack_calibration_edit_ = new QLineEdit;
  jack_calibration_edit_->setObjectName("jack_calibration");
  jack_calibration_edit_->setPlaceholderText(tr("calibration sidecar (base, mass)"));
  jack_calibration_edit_->setToolTip(
      tr("JACK: a sidecar with the base and the mass channel, in that order: unit V, scale "
         "(sensitivity), full_scale_v, ac_coupling_hz (docs/live.md)"));
  speed_box_ = new QComboBox;
  speed_box_->setObjectName("speed");
  speed_box_->addItem(tr("1\u00d7 (real time)"), 1.0);
  speed_box_->addItem(tr("10\u00d7"), 10.0);
  speed_box_->addItem(tr("100\u00d7"), 100.0);
  speed_box_->addItem(tr("max"), 0.0);
  speed_box_->setToolTip(
      tr("Replay: changes the speed at once. Rig: used at the next Start. max: as fast as the "
         "acquisition takes the samples"));
  start_button_ = new QPushButton(tr("Start"));
  start_button_->setObjectName("start");
  stop_button_ = new QPushButton(tr("Stop"));
  stop_button_->setObjectName("stop");
  stop_button_->setEnabled(false);
  connect(start_button_, &QPushButton::clicked, this, &LiveSourceControls::start_requested);
  connect(stop_button_, &QPushButton::clicked, this, &LiveSourceControls::stop_requested);
  auto* run_row = new QHBoxLayout;
  run_row->addWidget(start_button_);
  run_row->addWidget(stop_button_);
  auto* source_form = new QFormLayout(source_group);
  source_form->addRow(source_box_);
  source_form->addRow(tr("File"), path_row);
  source_form->addRow(QString(), loop_box_);
  source_form->addRow(tr("Port"), port_box_);
  source_form->addRow(tr("JACK server"), jack_server_row);
  source_form->addRow(tr("Base port"), jack_port_boxes_[0]);
  source_form->addRow(QString(), jack_meters_[0]);
  source_form->addRow(tr("Mass port"), jack_port_boxes_[1]);
  source_form->addRow(QString(), jack_meters_[1]);
  source_form->addRow(tr("Calibration"), jack_calibration_edit_);
  source_form->addRow(tr("Speed"), speed_box_);
  source_form->addRow(run_row);
  connect(source_box_, &QComboBox::currentIndexChanged, this, [this] {
    update_enabled();
    Q_EMIT settings_edited();
  });
  connect(speed_box_, &QComboBox::currentIndexChanged, this, [this] {
    Q_EMIT speed_changed(speed_box_->currentData().toDouble());
    Q_EMIT settings_edited();
  });
  connect(replay_path_edit_, &QLineEdit::editingFinished, this,
          &LiveSourceControls::settings_edited);
  connect(replay_path_edit_, &QLineEdit::textChanged, this, &LiveSourceControls::settings_edited);
  connect(loop_box_, &QCheckBox::toggled, this, &LiveSourceControls::settings_edited);
  connect(port_box_, &QSpinBox::valueChanged, this, &LiveSourceControls::settings_edited);
  for (QLineEdit* edit : {jack_server_edit_, jack_calibration_edit_}) {
    connect(edit, &QLineEdit::textChanged, this, &LiveSourceControls::settings_edited);
  }
  for (QComboBox* box : jack_port_boxes_) {
    connect(box, &QComboBox::currentTextChanged, this, &LiveSourceControls::settings_edited);
  }
  return source_group;
}

// The virtual rig's excitation: the well it starts in, f0 and the frequency, a level step.
QGroupBox* LiveSourceControls::make_rig_group() {
  auto* rig_group = new QGroupBox(tr("Virtual rig"));
  rig_group_ = rig_group;
  well_box_ = new QComboBox;
  well_box_->addItem(tr("starts in z\u208a*"));
  well_box_->addItem(tr("starts in z\u208b*"));
  well_box_->setToolTip(tr("The well the rig starts in (used at the next Start)"));
  f0_box_ = new QDoubleSpinBox;
  f0_box_->setObjectName("f0");
  f0_box_->setRange(0.0, 5.0);
  f0_box_->setDecimals(3);
  f0_box_->setSingleStep(0.1);
  f0_box_->setValue(0.5);
  f0_box_->setSuffix(tr(" N"));
  f0_box_->setToolTip(tr("Forcing amplitude f\u2080 of f = \u2212m b\u0308 (0: the table rests)"));
  frequency_box_ = new QDoubleSpinBox;
  frequency_box_->setObjectName("frequency");
  frequency_box_->setRange(0.5, 100.0);
  frequency_box_->setDecimals(2);
  frequency_box_->setValue(9.0);
  frequency_box_->setSuffix(tr(" Hz"));
  set_button_ = new QPushButton(tr("Set"));
  set_button_->setObjectName("set_excitation");
  set_button_->setToolTip(tr("Ramp the table to f\u2080 at \u03bd (0.5 s ramp)"));
  connect(set_button_, &QPushButton::clicked, this,
          [this] { Q_EMIT excitation_requested(f0_box_->value(), frequency_box_->value()); });
  step_box_ = new QDoubleSpinBox;
  step_box_->setRange(0.001, 2.0);
  step_box_->setDecimals(3);
  step_box_->setSingleStep(0.05);
  step_box_->setValue(0.1);
  step_box_->setSuffix(tr(" N"));
  step_button_ = new QPushButton(tr("Step +\u0394N"));
  step_button_->setObjectName("step_excitation");
  step_button_->setToolTip(
      tr("f\u2080 += \u0394N at the same \u03bd: the next stepped-sine level"));
  connect(step_button_, &QPushButton::clicked, this, &LiveSourceControls::step_requested);
  auto* f0_row = new QHBoxLayout;
  f0_row->addWidget(f0_box_, 1);
  f0_row->addWidget(set_button_);
  auto* step_row = new QHBoxLayout;
  step_row->addWidget(step_box_, 1);
  step_row->addWidget(step_button_);
  rig_now_label_ = new QLabel(QStringLiteral("\u2014"));
  rig_now_label_->setObjectName("rig_now");
  rig_now_label_->setToolTip(tr("The excitation the rig runs now (operator or schedule)"));
  auto* rig_form = new QFormLayout(rig_group);
  rig_form->addRow(tr("Now"), rig_now_label_);
  rig_form->addRow(tr("Well"), well_box_);
  rig_form->addRow(tr("f\u2080"), f0_row);
  rig_form->addRow(tr("\u03bd"), frequency_box_);
  rig_form->addRow(tr("\u0394N"), step_row);
  for (QDoubleSpinBox* box : {f0_box_, frequency_box_, step_box_}) {
    connect(box, &QDoubleSpinBox::valueChanged, this, &LiveSourceControls::settings_edited);
  }
  connect(well_box_, &QComboBox::currentIndexChanged, this, &LiveSourceControls::settings_edited);
  return rig_group;
}

// The replay's pause and seek.
QGroupBox* LiveSourceControls::make_replay_group() {
  auto* replay_group = new QGroupBox(tr("Replay"));
  replay_group_ = replay_group;
  replay_pause_button_ = new QPushButton(tr("Pause"));
  replay_pause_button_->setObjectName("replay_pause");
  replay_pause_button_->setCheckable(true);
  connect(replay_pause_button_, &QPushButton::toggled, this,
          &LiveSourceControls::replay_pause_toggled);
  seek_slider_ = new QSlider(Qt::Horizontal);
  seek_slider_->setObjectName("seek");
  seek_slider_->setRange(0, 1000);
  seek_slider_->setToolTip(tr("Position in the file: drag to seek (a discontinuity is logged)"));
  connect(seek_slider_, &QSlider::sliderReleased, this,
          [this] { Q_EMIT seek_requested(1e-3 * seek_slider_->value()); });
  seek_label_ = new QLabel(QStringLiteral("\u2014"));
  auto* replay_layout = new QGridLayout(replay_group);
  replay_layout->addWidget(replay_pause_button_, 0, 0);
  replay_layout->addWidget(seek_label_, 0, 1);
  replay_layout->addWidget(seek_slider_, 1, 0, 1, 2);
  return replay_group;
}

// Recording to a file, and marks in the event log.
QGroupBox* LiveSourceControls::make_record_group() {
  auto* record_group = new QGroupBox(tr("Recording"));
  record_button_ = new QPushButton(tr("Record\u2026"));
  record_button_->setObjectName("record");
  record_button_->setToolTip(tr("Record the stream losslessly (WAV, W64 or RF64, crash-safe)"));
  stop_recording_button_ = new QPushButton(tr("Stop recording"));
  stop_recording_button_->setObjectName("stop_recording");
  stop_recording_button_->setEnabled(false);
  connect(record_button_, &QPushButton::clicked, this, [this] {
    QString path = QFileDialog::getSaveFileName(this, tr("Record to"), QString(),
                                                tr("WAV (*.wav);;Wave64 (*.w64);;RF64 (*.rf64)"));
    if (path.isEmpty()) return;
    if (QFileInfo(path).suffix().isEmpty()) path += ".wav";
    Q_EMIT record_requested(path);
  });
  connect(stop_recording_button_, &QPushButton::clicked, this,
          &LiveSourceControls::stop_recording_requested);
  mark_edit_ = new QLineEdit;
  mark_edit_->setObjectName("mark_text");
  mark_edit_->setPlaceholderText(tr("note for the event log"));
  mark_button_ = new QPushButton(tr("Mark"));
  mark_button_->setObjectName("mark");
  connect(mark_button_, &QPushButton::clicked, this, [this] {
    Q_EMIT mark_requested(mark_edit_->text().isEmpty() ? tr("mark") : mark_edit_->text());
    mark_edit_->clear();
  });
  connect(mark_edit_, &QLineEdit::returnPressed, mark_button_, &QPushButton::click);
  auto* record_layout = new QGridLayout(record_group);
  record_layout->addWidget(record_button_, 0, 0);
  record_layout->addWidget(stop_recording_button_, 0, 1);
  record_layout->addWidget(mark_edit_, 1, 0);
  record_layout->addWidget(mark_button_, 1, 1);
  return record_group;
}

// The alarm limits on |z|, |b| and |f|.
QGroupBox* LiveSourceControls::make_alarm_group() {
  auto* alarm_group = new QGroupBox(tr("Alarms (next Start)"));
  const auto limit_box = [this](const char* name, double max, const QString& suffix,
                                const QString& tip) {
    auto* box = new QDoubleSpinBox;
    box->setObjectName(name);
    box->setRange(0.0, max);
    box->setDecimals(2);
    box->setSpecialValueText(tr("off"));
    box->setSuffix(suffix);
    box->setToolTip(tip);
    connect(box, &QDoubleSpinBox::valueChanged, this, &LiveSourceControls::settings_edited);
    return box;
  };
  alarm_z_box_ = limit_box("alarm_z", 100.0, tr(" mm"), tr("Alarm when |z| exceeds this"));
  alarm_b_box_ = limit_box("alarm_b", 1000.0, tr(" mm"),
                           tr("Alarm when the integrated table displacement |b| drifts past this"));
  alarm_f_box_ =
      limit_box("alarm_f", 100.0, tr(" N"), tr("Alarm when |f| = m|b\u0308| exceeds this"));
  auto* alarm_form = new QFormLayout(alarm_group);
  alarm_form->addRow(tr("|z| >"), alarm_z_box_);
  alarm_form->addRow(tr("|b| >"), alarm_b_box_);
  alarm_form->addRow(tr("|f| >"), alarm_f_box_);
  return alarm_group;
}

LiveSettings LiveSourceControls::settings() const {
  LiveSettings s;
  const int source = source_box_->currentIndex();
  s.source = source == 1   ? LiveSourceKind::Replay
             : source == 2 ? LiveSourceKind::Network
             : source == 3 ? LiveSourceKind::Jack
                           : LiveSourceKind::Rig;
  s.jack_server = jack_server_edit_->text().toStdString();
  s.jack_base_port = jack_port_boxes_[0]->currentText().toStdString();
  s.jack_mass_port = jack_port_boxes_[1]->currentText().toStdString();
  s.jack_calibration = jack_calibration_edit_->text().toStdString();
  s.replay_path = replay_path_edit_->text().toStdString();
  s.replay_loop = loop_box_->isChecked();
  s.port = port_box_->value();
  s.rig_f0_n = f0_box_->value();
  s.rig_frequency_hz = frequency_box_->value();
  s.rig_step_n = step_box_->value();
  s.rig_positive_well = well_box_->currentIndex() == 0;
  s.speed = speed_box_->currentData().toDouble();
  const auto limit = [](QDoubleSpinBox* box, double si_per_unit) -> std::optional<double> {
    if (box->value() <= box->minimum()) return std::nullopt;
    return box->value() * si_per_unit;
  };
  s.alarms.max_abs_z_m = limit(alarm_z_box_, 1e-3);
  s.alarms.max_abs_base_m = limit(alarm_b_box_, 1e-3);
  s.alarms.max_abs_force_n = limit(alarm_f_box_, 1.0);
  return s;
}

void LiveSourceControls::set_settings(const LiveSettings& s) {
  source_box_->setCurrentIndex(s.source == LiveSourceKind::Replay    ? 1
                               : s.source == LiveSourceKind::Network ? 2
                               : s.source == LiveSourceKind::Jack    ? 3
                                                                     : 0);
  jack_server_edit_->setText(qtext(s.jack_server));
  jack_port_boxes_[0]->setCurrentText(qtext(s.jack_base_port));
  jack_port_boxes_[1]->setCurrentText(qtext(s.jack_mass_port));
  jack_calibration_edit_->setText(qtext(s.jack_calibration));
  replay_path_edit_->setText(qtext(s.replay_path));
  loop_box_->setChecked(s.replay_loop);
  port_box_->setValue(s.port);
  f0_box_->setValue(s.rig_f0_n);
  frequency_box_->setValue(s.rig_frequency_hz);
  step_box_->setValue(s.rig_step_n);
  well_box_->setCurrentIndex(s.rig_positive_well ? 0 : 1);
  int speed = speed_box_->findData(s.speed);
  if (speed < 0) {
    speed_box_->addItem(QStringLiteral("%1\u00d7").arg(s.speed), s.speed);
    speed = speed_box_->count() - 1;
  }
  speed_box_->setCurrentIndex(speed);
  alarm_z_box_->setValue(s.alarms.max_abs_z_m ? 1e3 * *s.alarms.max_abs_z_m : 0.0);
  alarm_b_box_->setValue(s.alarms.max_abs_base_m ? 1e3 * *s.alarms.max_abs_base_m : 0.0);
  alarm_f_box_->setValue(s.alarms.max_abs_force_n ? *s.alarms.max_abs_force_n : 0.0);
  update_enabled();
}

void LiveSourceControls::set_rig_schedule(std::vector<daq::ExcitationStep> schedule) {
  rig_schedule_ = std::move(schedule);
}

void LiveSourceControls::show_state(bool live, bool rig, bool replay) {
  live_ = live;
  rig_ = rig;
  replay_ = replay;
  update_enabled();
}

void LiveSourceControls::update_enabled() {
  const int source = source_box_->currentIndex();
  replay_path_edit_->setEnabled(source == 1);
  browse_button_->setEnabled(source == 1);
  loop_box_->setEnabled(source == 1);
  port_box_->setEnabled(source == 2);
  for (QWidget* w :
       {static_cast<QWidget*>(jack_server_edit_), static_cast<QWidget*>(jack_list_button_),
        static_cast<QWidget*>(jack_port_boxes_[0]), static_cast<QWidget*>(jack_port_boxes_[1]),
        static_cast<QWidget*>(jack_calibration_edit_)}) {
    w->setEnabled(source == 3);
  }
  speed_box_->setEnabled(source != 2 && source != 3);
  const bool live = live_;
  rig_group_->setEnabled(source == 0 || rig_);
  set_button_->setEnabled(rig_ && live);
  step_button_->setEnabled(rig_ && live);
  replay_group_->setEnabled(replay_ && live);
  start_button_->setEnabled(!live);
  stop_button_->setEnabled(live);
  record_button_->setEnabled(live);
  mark_button_->setEnabled(live);
}

void LiveSourceControls::show_rig_excitation(const daq::ExcitationStep& now) {
  rig_now_label_->setText(
      tr("f\u2080 = %1 N at %2 Hz").arg(now.f0_n, 0, 'f', 3).arg(now.frequency_hz, 0, 'g', 4));
}

void LiveSourceControls::show_excitation_fields(double f0_n, double frequency_hz) {
  const QSignalBlocker block_f0(f0_box_), block_freq(frequency_box_);
  f0_box_->setValue(f0_n);
  frequency_box_->setValue(frequency_hz);
}

void LiveSourceControls::show_replay_position(double position_s, double duration_s) {
  seek_label_->setText(tr("%1 / %2 s").arg(position_s, 0, 'f', 1).arg(duration_s, 0, 'f', 1));
  if (!seek_slider_->isSliderDown() && duration_s > 0) {
    const QSignalBlocker block(seek_slider_);
    seek_slider_->setValue(static_cast<int>(1000.0 * position_s / duration_s));
  }
}

void LiveSourceControls::reset_replay_pause() { replay_pause_button_->setChecked(false); }

void LiveSourceControls::show_recording(bool recording) {
  stop_recording_button_->setEnabled(recording);
}

void LiveSourceControls::show_jack_peaks(const std::vector<double>& peaks_percent) {
  for (std::size_t c = 0; c < 2 && c < peaks_percent.size(); ++c) {
    jack_meters_[c]->setValue(static_cast<int>(std::lround(std::min(peaks_percent[c], 100.0))));
  }
}

void LiveSourceControls::set_jack_ports(const std::vector<std::string>& ports) {
  for (QComboBox* box : jack_port_boxes_) {
    const QString chosen = box->currentText();
    const QSignalBlocker block(box);
    box->clear();
    for (const std::string& port : ports) box->addItem(qtext(port));
    box->setCurrentText(chosen);
  }
}

double LiveSourceControls::f0_n() const { return f0_box_->value(); }

double LiveSourceControls::frequency_hz() const { return frequency_box_->value(); }

double LiveSourceControls::step_n() const { return step_box_->value(); }

QString LiveSourceControls::jack_server() const { return jack_server_edit_->text(); }

}  // namespace oscilab::ui

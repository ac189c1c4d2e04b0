#include "ui/live_monitor.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QSplitter>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "analysis/hbm/level_response.h"
#include "analysis/model/reference_models.h"
#include "analysis/rfs/cycle_loop.h"
#include "analysis/signal/amplitude_spectrum.h"
#include "daq/live/jack_source.h"
#include "daq/live/net_source.h"
#include "daq/live/replay_source.h"
#include "daq/live/source_factory.h"
#include "ui/background_job.h"
#include "ui/live_edc_plot_data.h"
#include "ui/live_event_row.h"
#include "ui/live_status_fields.h"
#include "ui/plot_helpers.h"
#include "ui/well_colours.h"

namespace oscilab::ui {

/// The model's EDC at the prediction levels, both wells (written by the worker).
struct LiveMonitor::Prediction {
  std::shared_ptr<const analysis::Model> model;
  double frequency_hz = 0.0;
  std::vector<double> levels_n;
  analysis::LevelResponse wells[2];  // positive, negative
  std::string error;
};

namespace {

// Display rate: a frame every 16 ms (≤ 60 Hz). The slower parts run at most one per frame, so
// that no frame does everything at once (the event loop stays responsive).
constexpr int kFrameMs = 16;
enum SlowPart { kStatusPart, kEdcPart, kSlicesPart, kCyclePart, kSlowParts };
// Period of each: the status strip and the event log, the EDC plot, the slices, the loop and
// the spectrum.
constexpr qint64 kPartPeriodMs[kSlowParts] = {100, 250, 250, 250};
constexpr int kMaxLogRows = 2000;  // the event log keeps the newest rows
// Seconds of history the spectrum and the loop look at: the derived z lags the stream by the
// acquisition's derived_latency_s (2 s), so 6 s hold about 4 s of z (36 cycles at 9 Hz).
constexpr double kAnalysisSpanS = 6.0;
// At most this much history is read at once for the restoring-force slices (a first read after
// a long run, or after the slices were reset).
constexpr double kMaxSliceCatchUpS = 60.0;
constexpr int kSliceMaxPoints = 6000;  // per slice: enough for the cloud, quick to draw
const QColor kAmber(255, 196, 70);
const QColor kRed(214, 60, 50);
const QColor kOtherWell = well_colour("cross-well");

enum Trace { kBaseTrace, kBTrace, kMassTrace, kZTrace, kForceTrace, kTraceCount };
const QColor kTraceColours[kTraceCount] = {QColor(0, 114, 178), QColor(0, 158, 115),
                                           QColor(204, 121, 167), QColor(20, 20, 20),
                                           QColor(213, 94, 0)};

QString qs(const std::string& s) { return QString::fromStdString(s); }

QString severity_style(Severity severity) {
  switch (severity) {
    case Severity::Fault:
      return QStringLiteral(
          "QLabel { background: rgb(214,60,50); color: white; border-radius: 3px; padding: 1px "
          "4px; "
          "}");
    case Severity::Warning:
      return QStringLiteral(
          "QLabel { background: rgb(255,196,70); border-radius: 3px; padding: 1px 4px; }");
    default:
      return QStringLiteral("QLabel { padding: 1px 4px; }");
  }
}

QCustomPlot* make_plot(const QString& name, const QString& title, const QString& x_label,
                       const QString& y_label) {
  auto* plot = new QCustomPlot;
  plot->setObjectName(name);
  plot->setMinimumSize(220, 160);
  plot->plotLayout()->insertRow(0);
  QFont font = plot->font();
  font.setBold(true);
  auto* heading = new QCPTextElement(plot, title, font);
  heading->setMargins(QMargins(0, 2, 0, 0));
  plot->plotLayout()->addElement(0, 0, heading);
  plot->xAxis->setLabel(x_label);
  plot->yAxis->setLabel(y_label);
  plot->xAxis->setNumberFormat("gb");
  plot->yAxis->setNumberFormat("gb");
  for (QCPAxis* axis : {plot->xAxis2, plot->yAxis2}) {  // a frame: top and right as lines
    axis->setVisible(true);
    axis->setTicks(false);
    axis->setTickLabels(false);
  }
  QFont legend_font = plot->font();
  legend_font.setPointSizeF(legend_font.pointSizeF() * 0.85);
  plot->legend->setFont(legend_font);
  plot->legend->setBrush(QColor(255, 255, 255, 210));
  return plot;
}

// Lists `plottable` in its plot's legend only while it has something to show.
void show_in_legend(QCPAbstractPlottable* plottable, bool show) {
  QCPLegend* legend = plottable->parentPlot()->legend;
  if (show && !legend->hasItemWithPlottable(plottable)) plottable->addToLegend();
  if (!show && legend->hasItemWithPlottable(plottable)) plottable->removeFromLegend();
}

QCPGraph* scatter_graph(QCustomPlot* plot, const QColor& colour, const QString& name) {
  QCPGraph* graph = plot->addGraph();
  graph->setLineStyle(QCPGraph::lsNone);
  graph->setScatterStyle(disc_markers(colour, 3));
  graph->setPen(QPen(colour));
  graph->setName(name);
  graph->setAdaptiveSampling(true);
  return graph;
}

// Range of the finite values of `v` (lo > hi when there are none) and their largest |value|.
void finite_range(const std::vector<double>& v, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (double x : v) {
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  }
}

// Axis range over the finite values of x, with a margin; unchanged without any.
void fit_axis(QCPAxis* axis, double lo, double hi, double margin = 0.06) {
  if (!(lo <= hi)) return;
  const double pad = hi > lo ? margin * (hi - lo) : std::max(std::abs(hi), 1e-12) * 0.1;
  axis->setRange(lo - pad, hi + pad);
}

QString trace_name(int trace, const std::optional<daq::Sidecar>& layout) {
  daq::Quantity base = daq::Quantity::Acceleration, mass = daq::Quantity::Displacement;
  bool relative = false;
  if (layout) {
    for (const daq::ChannelInfo& c : layout->channels) {
      if (c.role == daq::ChannelRole::Base) base = c.quantity;
      if (c.role == daq::ChannelRole::Mass) mass = c.quantity;
      if (c.role == daq::ChannelRole::Relative) relative = true, mass = c.quantity;
    }
  }
  switch (trace) {
    case kBaseTrace:
      return base == daq::Quantity::Acceleration ? QObject::tr("b\u0308 table acceleration")
             : base == daq::Quantity::Velocity   ? QObject::tr("b\u0307 table velocity")
                                                 : QObject::tr("b table (measured)");
    case kBTrace:
      return QObject::tr("b table displacement (integrated, 2 s behind)");
    case kMassTrace:
      return relative ? QObject::tr("z relative displacement (measured)")
             : mass == daq::Quantity::Displacement ? QObject::tr("y mass position (vibrometer)")
                                                   : QObject::tr("mass channel");
    case kZTrace:
      return QObject::tr("z = y \u2212 b (2 s behind)");
    default:
      return QObject::tr("f = \u2212m b\u0308");
  }
}

QString trace_symbol(int trace) {
  static const char* symbols[kTraceCount] = {"b\u0308", "b", "y", "z", "f"};
  return QString::fromUtf8(symbols[trace]);
}

std::string trace_si_unit(int trace, const std::optional<daq::Sidecar>& layout) {
  if (trace == kBTrace || trace == kZTrace) return "m";
  if (trace == kForceTrace) return "N";
  if (layout) {
    for (const daq::ChannelInfo& c : layout->channels) {
      if (trace == kBaseTrace && c.role == daq::ChannelRole::Base) return si_unit_of(c.quantity);
      if (trace == kMassTrace &&
          (c.role == daq::ChannelRole::Mass || c.role == daq::ChannelRole::Relative)) {
        return si_unit_of(c.quantity);
      }
    }
  }
  return trace == kBaseTrace ? "m/s^2" : "m";
}

}  // namespace

LiveMonitor::LiveMonitor(QWidget* parent)
    : QWidget(parent),
      clock_(std::make_unique<QElapsedTimer>()),
      prediction_model_(std::make_shared<const analysis::Model>(analysis::paper_model())),
      prediction_label_(tr("paper model (Tables 1, 3)")) {
  clock_->start();
  trace_units_.resize(kTraceCount);
  trace_ranges_.resize(kTraceCount);
  analysis::StreamingSlices::Options rfs;
  rfs.max_points = kSliceMaxPoints;
  rfs_ = analysis::StreamingSlices(rfs);

  prediction_job_ = new BackgroundJob(this);
  connect(prediction_job_, &BackgroundJob::finished, this, &LiveMonitor::on_prediction_finished);
  frame_timer_ = new QTimer(this);
  frame_timer_->setInterval(kFrameMs);
  connect(frame_timer_, &QTimer::timeout, this, &LiveMonitor::tick);

  auto* panel = new QWidget;
  build_controls(panel);
  auto* scroll = new QScrollArea;
  scroll->setWidget(panel);
  scroll->setWidgetResizable(true);
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  scroll->setMinimumWidth(panel->sizeHint().width() + 20);
  scroll->setFrameShape(QFrame::NoFrame);

  build_plots();

  message_label_ = new QLabel;
  message_label_->setObjectName("live_message");
  message_label_->setWordWrap(true);
  message_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  message_label_->setText(tr("Choose a source and press Start."));
  message_label_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);

  // The status strip: two rows of figures. Each label is as wide as its widest expected text,
  // whatever it shows now, so that a changing figure never changes the page's layout.
  auto* strip = new QWidget;
  strip->setObjectName("status_strip");
  auto* strip_layout = new QGridLayout(strip);
  strip_layout->setContentsMargins(0, 0, 0, 0);
  strip_layout->setHorizontalSpacing(6);
  strip_layout->setVerticalSpacing(2);
  const std::map<std::string, QString> widest = {
      {"source", "replay stepped_positive.flac (running)"},
      {"rate", "rate 51200 Hz \u00d7100"},
      {"time", "t 00000.0 s"},
      {"samples", "samples 000000000"},
      {"gaps", "gaps 000000 (000)"},
      {"duplicates", "dup 0000"},
      {"reordered", "reord 0000"},
      {"nan", "NaN 000000"},
      {"saturated", "sat 000000"},
      {"overflow", "overflow 00000"},
      {"queue", "queue 000/256"},
      {"recording", "rec \u25cf 00000.0 s"},
      {"cycles", "cycles 000000 (000 excl.)"},
      {"levels", "levels 000"},
      {"latency", "EDC latency 0000 ms"},
      {"alarms", "alarms 000"},
      {"errors", "errors 000"}};
  const std::vector<StatusField> fields =
      status_fields({}, {}, fault_tracker_, 0.0, 0.0);  // the keys, in order
  // The source on the left over both rows (it wraps), the other figures in two rows of 8.
  constexpr int kPerRow = 8;
  std::vector<int> column_width(kPerRow, 0);
  for (std::size_t i = 1; i < fields.size(); ++i) {
    const auto text = widest.find(fields[i].key);
    const int width =
        fontMetrics().horizontalAdvance(text != widest.end() ? text->second : "0000000") + 14;
    column_width[(i - 1) % kPerRow] = std::max(column_width[(i - 1) % kPerRow], width);
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    auto* label = new QLabel;
    label->setObjectName(qs("status_" + fields[i].key));
    label->setStyleSheet(severity_style(Severity::Normal));
    label->setProperty("severity", 0);
    if (i == 0) {
      label->setWordWrap(true);
      label->setFixedWidth(fontMetrics().horizontalAdvance(widest.at("source")) / 2 + 30);
      strip_layout->addWidget(label, 0, 0, 2, 1);
    } else {
      const int column = static_cast<int>(i - 1) % kPerRow;
      label->setFixedWidth(column_width[std::size_t(column)]);
      strip_layout->addWidget(label, static_cast<int>(i - 1) / kPerRow, column + 1);
    }
    status_labels_.emplace_back(fields[i].key, label);
  }
  strip_layout->setColumnStretch(kPerRow + 1, 1);
  warning_label_ = new QLabel;
  warning_label_->setObjectName("level_warning");
  warning_label_->setStyleSheet(severity_style(Severity::Normal));
  warning_label_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);

  // Traces with their window controls.
  window_box_ = new QDoubleSpinBox;
  window_box_->setObjectName("window_s");
  window_box_->setRange(1.0, 600.0);
  window_box_->setDecimals(0);
  window_box_->setValue(10.0);
  window_box_->setSuffix(tr(" s"));
  window_box_->setToolTip(tr("Time shown by the traces (up to the 10 minutes kept)"));
  connect(window_box_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
    timeline_.set_window_s(v);
    sync_scroll_bar();
    refresh_traces();
    emit_settings();
  });
  pause_view_button_ = new QPushButton(tr("Pause view"));
  pause_view_button_->setObjectName("pause_view");
  pause_view_button_->setCheckable(true);
  pause_view_button_->setToolTip(
      tr("Freeze the traces and scroll back over the last 10 minutes; the acquisition goes on"));
  connect(pause_view_button_, &QPushButton::toggled, this, &LiveMonitor::set_view_paused);
  scroll_bar_ = new QScrollBar(Qt::Horizontal);
  scroll_bar_->setObjectName("view_scroll");
  scroll_bar_->setToolTip(tr("Scroll back over the history (pauses the view)"));
  connect(scroll_bar_, &QScrollBar::valueChanged, this,
          [this](int value) { scroll_view_to(0.1 * value); });
  auto* trace_controls = new QHBoxLayout;
  trace_controls->addWidget(new QLabel(tr("Window")));
  trace_controls->addWidget(window_box_);
  trace_controls->addWidget(pause_view_button_);
  trace_controls->addWidget(scroll_bar_, 1);
  auto* trace_page = new QWidget;
  auto* trace_layout = new QVBoxLayout(trace_page);
  trace_layout->setContentsMargins(0, 0, 0, 0);
  trace_layout->addWidget(trace_plot_, 1);
  trace_layout->addLayout(trace_controls);

  // Analysis: EDC on top, loop and spectrum, then the slices.
  auto* middle = new QSplitter(Qt::Horizontal);
  middle->addWidget(loop_plot_);
  middle->addWidget(spectrum_plot_);
  auto* bottom = new QSplitter(Qt::Horizontal);
  bottom->addWidget(stiffness_plot_);
  bottom->addWidget(damping_plot_);
  auto* analysis = new QSplitter(Qt::Vertical);
  analysis->addWidget(edc_plot_);
  analysis->addWidget(middle);
  analysis->addWidget(bottom);
  analysis->setChildrenCollapsible(false);

  auto* plots = new QSplitter(Qt::Horizontal);
  plots->addWidget(trace_page);
  plots->addWidget(analysis);
  plots->setStretchFactor(0, 5);
  plots->setStretchFactor(1, 6);
  plots->setChildrenCollapsible(false);

  auto* right = new QVBoxLayout;
  right->setContentsMargins(0, 0, 0, 0);
  right->addWidget(message_label_);
  right->addWidget(strip);
  right->addWidget(warning_label_);
  right->addWidget(plots, 1);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addWidget(scroll);
  layout->addLayout(right, 1);

  update_source_controls();
  refresh_status();
}

LiveMonitor::~LiveMonitor() {
  frame_timer_->stop();
  acquisition_.reset();  // stops the source and joins the threads
}

void LiveMonitor::build_controls(QWidget* panel) {
  auto* layout = new QVBoxLayout(panel);
  layout->setContentsMargins(0, 0, 4, 0);

  // Source.
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
  connect(jack_list_button_, &QPushButton::clicked, this, [this] { list_jack_ports(); });
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
  connect(start_button_, &QPushButton::clicked, this, [this] { start(); });
  connect(stop_button_, &QPushButton::clicked, this, &LiveMonitor::stop);
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
    update_source_controls();
    emit_settings();
  });
  connect(speed_box_, &QComboBox::currentIndexChanged, this, [this] {
    if (replay_) replay_->set_speed(speed_box_->currentData().toDouble());
    emit_settings();
  });
  connect(replay_path_edit_, &QLineEdit::editingFinished, this, &LiveMonitor::emit_settings);
  connect(replay_path_edit_, &QLineEdit::textChanged, this, &LiveMonitor::emit_settings);
  connect(loop_box_, &QCheckBox::toggled, this, &LiveMonitor::emit_settings);
  connect(port_box_, &QSpinBox::valueChanged, this, &LiveMonitor::emit_settings);
  for (QLineEdit* edit : {jack_server_edit_, jack_calibration_edit_}) {
    connect(edit, &QLineEdit::textChanged, this, &LiveMonitor::emit_settings);
  }
  for (QComboBox* box : jack_port_boxes_) {
    connect(box, &QComboBox::currentTextChanged, this, &LiveMonitor::emit_settings);
  }

  // The rig.
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
          [this] { set_excitation(f0_box_->value(), frequency_box_->value()); });
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
  connect(step_button_, &QPushButton::clicked, this, &LiveMonitor::step_excitation);
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
    connect(box, &QDoubleSpinBox::valueChanged, this, &LiveMonitor::emit_settings);
  }
  connect(well_box_, &QComboBox::currentIndexChanged, this, &LiveMonitor::emit_settings);

  // The replay.
  auto* replay_group = new QGroupBox(tr("Replay"));
  replay_group_ = replay_group;
  replay_pause_button_ = new QPushButton(tr("Pause"));
  replay_pause_button_->setObjectName("replay_pause");
  replay_pause_button_->setCheckable(true);
  connect(replay_pause_button_, &QPushButton::toggled, this, [this](bool paused) {
    if (replay_) replay_->set_paused(paused);
  });
  seek_slider_ = new QSlider(Qt::Horizontal);
  seek_slider_->setObjectName("seek");
  seek_slider_->setRange(0, 1000);
  seek_slider_->setToolTip(tr("Position in the file: drag to seek (a discontinuity is logged)"));
  connect(seek_slider_, &QSlider::sliderReleased, this, [this] {
    if (replay_) replay_->seek(1e-3 * seek_slider_->value() * replay_->duration_s());
  });
  seek_label_ = new QLabel(QStringLiteral("\u2014"));
  auto* replay_layout = new QGridLayout(replay_group);
  replay_layout->addWidget(replay_pause_button_, 0, 0);
  replay_layout->addWidget(seek_label_, 0, 1);
  replay_layout->addWidget(seek_slider_, 1, 0, 1, 2);

  // Recording and marks.
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
    start_recording(path);
  });
  connect(stop_recording_button_, &QPushButton::clicked, this, &LiveMonitor::stop_recording);
  mark_edit_ = new QLineEdit;
  mark_edit_->setObjectName("mark_text");
  mark_edit_->setPlaceholderText(tr("note for the event log"));
  mark_button_ = new QPushButton(tr("Mark"));
  mark_button_->setObjectName("mark");
  connect(mark_button_, &QPushButton::clicked, this, [this] {
    mark(mark_edit_->text().isEmpty() ? tr("mark") : mark_edit_->text());
    mark_edit_->clear();
  });
  connect(mark_edit_, &QLineEdit::returnPressed, mark_button_, &QPushButton::click);
  auto* record_layout = new QGridLayout(record_group);
  record_layout->addWidget(record_button_, 0, 0);
  record_layout->addWidget(stop_recording_button_, 0, 1);
  record_layout->addWidget(mark_edit_, 1, 0);
  record_layout->addWidget(mark_button_, 1, 1);

  // Alarm limits.
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
    connect(box, &QDoubleSpinBox::valueChanged, this, &LiveMonitor::emit_settings);
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

  // Event log.
  auto* log_group = new QGroupBox(tr("Events"));
  event_log_ = new QTableWidget(0, 3);
  event_log_->setObjectName("event_log");
  event_log_->setHorizontalHeaderLabels({tr("t"), tr("kind"), tr("what")});
  event_log_->horizontalHeader()->setStretchLastSection(true);
  event_log_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  event_log_->horizontalHeader()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
  event_log_->verticalHeader()->hide();
  event_log_->verticalHeader()->setDefaultSectionSize(event_log_->fontMetrics().height() + 4);
  event_log_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  event_log_->setSelectionBehavior(QAbstractItemView::SelectRows);
  event_log_->setWordWrap(false);
  event_log_->setMinimumHeight(140);
  auto* log_layout = new QVBoxLayout(log_group);
  log_layout->setContentsMargins(2, 2, 2, 2);
  log_layout->addWidget(event_log_);

  layout->addWidget(source_group);
  layout->addWidget(rig_group);
  layout->addWidget(replay_group);
  layout->addWidget(record_group);
  layout->addWidget(alarm_group);
  layout->addWidget(log_group, 1);
  panel->setMinimumWidth(270);
  panel->setMaximumWidth(340);
}

void LiveMonitor::build_plots() {
  // Traces: one axis rect per trace, stacked over a shared time axis.
  trace_plot_ = new QCustomPlot;
  trace_plot_->setObjectName("trace_plot");
  trace_plot_->setMinimumSize(320, 400);
  trace_plot_->plotLayout()->clear();
  trace_plot_->plotLayout()->setRowSpacing(2);
  auto* margins = new QCPMarginGroup(trace_plot_);
  for (int k = 0; k < kTraceCount; ++k) {
    auto* rect = new QCPAxisRect(trace_plot_);
    trace_plot_->plotLayout()->addElement(k, 0, rect);
    rect->setMarginGroup(QCP::msLeft | QCP::msRight, margins);
    QCPAxis* time_axis = rect->axis(QCPAxis::atBottom);
    QCPAxis* value_axis = rect->axis(QCPAxis::atLeft);
    const bool bottom = k == kTraceCount - 1;
    time_axis->setTickLabels(bottom);
    if (bottom) time_axis->setLabel(tr("stream time [s]"));
    value_axis->setNumberFormat("gb");
    value_axis->setLabel(trace_symbol(k));
    for (QCPAxis::AxisType side : {QCPAxis::atTop, QCPAxis::atRight}) {
      rect->axis(side)->setVisible(true);
      rect->axis(side)->setTicks(false);
      rect->axis(side)->setTickLabels(false);
    }
    QCPGraph* graph = trace_plot_->addGraph(time_axis, value_axis);
    graph->setPen(QPen(kTraceColours[k], 1.0));
    graph->setAntialiased(false);
    auto* name = new QCPItemText(trace_plot_);
    name->setObjectName("trace_name");
    name->setClipAxisRect(rect);
    name->position->setAxisRect(rect);
    name->position->setType(QCPItemPosition::ptAxisRectRatio);
    name->position->setCoords(0.01, 0.03);
    name->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
    name->setColor(kTraceColours[k].darker(130));
    name->setBrush(QColor(255, 255, 255, 200));
    name->setText(trace_name(k, std::nullopt));
    trace_names_.push_back(name);
    trace_rects_.push_back(rect);
    trace_graphs_.push_back(graph);
  }
  connect(trace_plot_, &QCustomPlot::afterReplot, this, [this] { ++frames_; });

  // EDC against f0 (Fig. 10, with the model as Fig. 15).
  edc_plot_ = make_plot("edc_plot", tr("Energy dissipated per cycle, level by level (Fig. 10)"),
                        tr("forcing amplitude f\u2080 [N]"), tr("EDC [mJ]"));
  edc_plot_->setMinimumHeight(230);
  edc_plot_->legend->setVisible(true);
  edc_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
  const QString well_names[3] = {tr("z\u208a* measured \u00b13\u03c3"),
                                 tr("z\u208b* measured \u00b13\u03c3"), tr("cross-well / unknown")};
  const QColor well_colours[3] = {well_colour("positive"), well_colour("negative"), kOtherWell};
  for (int w = 0; w < 2; ++w) {
    model_graphs_[w] = edc_plot_->addGraph();
    model_graphs_[w]->setPen(QPen(well_colours[w], 1.5, Qt::DashDotLine));
    model_graphs_[w]->setName((w == 0 ? tr("z\u208a* ") : tr("z\u208b* ")) + prediction_label_ +
                              tr(", HBM"));
    model_graphs_[w]->removeFromLegend();  // until drawn
  }
  for (int w = 0; w < 3; ++w) {
    QCPGraph* graph = edc_plot_->addGraph();
    graph->setName(well_names[w]);
    graph->setLineStyle(QCPGraph::lsNone);
    graph->setPen(QPen(well_colours[w], 1.5));
    graph->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, well_colours[w],
                                           well_colours[w].lighter(170), 6));
    auto* bars = new QCPErrorBars(edc_plot_->xAxis, edc_plot_->yAxis);
    bars->removeFromLegend();
    bars->setDataPlottable(graph);
    bars->setPen(QPen(well_colours[w], 1.0));
    bars->setWhiskerWidth(5);
    edc_graphs_[w] = graph;
    edc_bars_[w] = bars;
  }
  for (QCPGraph* graph : edc_graphs_) graph->removeFromLegend();  // listed once they have points
  current_graph_ = edc_plot_->addGraph();
  current_graph_->setName(tr("level being filled"));
  current_graph_->setLineStyle(QCPGraph::lsNone);
  current_graph_->setPen(QPen(Qt::black, 1.5));
  current_graph_->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssDiamond, 9));
  current_graph_->removeFromLegend();
  auto* current_bars = new QCPErrorBars(edc_plot_->xAxis, edc_plot_->yAxis);
  current_bars->removeFromLegend();
  current_bars->setDataPlottable(current_graph_);
  current_bars->setPen(QPen(Qt::black, 1.0, Qt::DotLine));
  edc_bars_[3] = current_bars;
  edc_plot_->xAxis->setRange(0.0, 2.8);
  edc_plot_->yAxis->setRange(0.0, 1.0);
  set_plot_hint(edc_plot_, tr("Levels appear here as the stepped sine runs."));

  // The loop of the current cycle (Fig. 9).
  loop_plot_ = make_plot("loop_plot", tr("f\u2013z loop of the current cycle (Fig. 9)"),
                         tr("z [mm]"), tr("f [N]"));
  auto* loop = new QCPCurve(loop_plot_->xAxis, loop_plot_->yAxis);
  loop->setPen(QPen(well_colour("positive"), 1.5));
  loop->setName(tr("current cycle"));
  set_plot_hint(loop_plot_, tr("Needs a whole cycle of z (2 s behind)."));

  // Spectrum of z.
  spectrum_plot_ = make_plot("spectrum_plot", tr("Spectrum of z, last seconds"),
                             tr("frequency [Hz]"), tr("|Z| [m]"));
  spectrum_plot_->yAxis->setScaleType(QCPAxis::stLogarithmic);
  auto log_ticker = QSharedPointer<QCPAxisTickerLog>::create();
  log_ticker->setSubTickCount(0);
  spectrum_plot_->yAxis->setTicker(log_ticker);
  spectrum_plot_->yAxis->setNumberFormat("eb");
  spectrum_plot_->yAxis->setNumberPrecision(0);
  QCPGraph* spectrum = spectrum_plot_->addGraph();
  spectrum->setPen(QPen(QColor(20, 20, 20), 1.0));
  spectrum->setName(tr("|Z(f)| (Hann)"));
  QCPGraph* harmonics = spectrum_plot_->addGraph();
  harmonics->setLineStyle(QCPGraph::lsImpulse);
  harmonics->setPen(QPen(QColor(213, 94, 0, 120), 5));
  harmonics->setScatterStyle(
      QCPScatterStyle(QCPScatterStyle::ssCircle, QColor(213, 94, 0), Qt::white, 6));
  harmonics->setName(tr("harmonics h\u03bd"));
  spectrum_plot_->legend->setVisible(true);
  spectrum_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignRight);
  spectrum_plot_->xAxis->setRange(0.0, 80.0);
  spectrum_plot_->yAxis->setRange(1e-8, 1e-2);
  set_plot_hint(spectrum_plot_, tr("Needs a few seconds of z."));

  // The restoring force slices (§3.1–3.2, Fig. 7b, 7c).
  stiffness_plot_ =
      make_plot("stiffness_plot", tr("Stiffness slice: R at small |\u017c| (Fig. 7b)"),
                tr("z [mm]"), tr("R [N]"));
  damping_plot_ =
      make_plot("damping_plot", tr("Damping slice: R near the current z\u0304 (Fig. 7c)"),
                tr("\u017c [mm/s]"), tr("R [N]"));
  for (QCustomPlot* plot : {stiffness_plot_, damping_plot_}) {
    scatter_graph(plot, well_colour("positive"), tr("z\u208a* well"))->removeFromLegend();
    scatter_graph(plot, well_colour("negative"), tr("z\u208b* well"))->removeFromLegend();
    plot->legend->setVisible(true);
    plot->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
    set_plot_hint(plot, tr("Grows as cycles arrive (R, z, \u017c are 2 s behind)."));
  }
}

// --- settings --------------------------------------------------------------------------------

LiveSettings LiveMonitor::settings() const {
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
  s.window_s = window_box_->value();
  const auto limit = [](QDoubleSpinBox* box, double si_per_unit) -> std::optional<double> {
    if (box->value() <= box->minimum()) return std::nullopt;
    return box->value() * si_per_unit;
  };
  s.alarms.max_abs_z_m = limit(alarm_z_box_, 1e-3);
  s.alarms.max_abs_base_m = limit(alarm_b_box_, 1e-3);
  s.alarms.max_abs_force_n = limit(alarm_f_box_, 1.0);
  return s;
}

void LiveMonitor::set_settings(const LiveSettings& s) {
  set_controls(s);
  emit_settings();
}

void LiveMonitor::set_controls(const LiveSettings& s) {
  applying_settings_ = true;
  source_box_->setCurrentIndex(s.source == LiveSourceKind::Replay    ? 1
                               : s.source == LiveSourceKind::Network ? 2
                               : s.source == LiveSourceKind::Jack    ? 3
                                                                     : 0);
  jack_server_edit_->setText(qs(s.jack_server));
  jack_port_boxes_[0]->setCurrentText(qs(s.jack_base_port));
  jack_port_boxes_[1]->setCurrentText(qs(s.jack_mass_port));
  jack_calibration_edit_->setText(qs(s.jack_calibration));
  replay_path_edit_->setText(qs(s.replay_path));
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
  window_box_->setValue(s.window_s);
  alarm_z_box_->setValue(s.alarms.max_abs_z_m ? 1e3 * *s.alarms.max_abs_z_m : 0.0);
  alarm_b_box_->setValue(s.alarms.max_abs_base_m ? 1e3 * *s.alarms.max_abs_base_m : 0.0);
  alarm_f_box_->setValue(s.alarms.max_abs_force_n ? *s.alarms.max_abs_force_n : 0.0);
  applying_settings_ = false;
  update_source_controls();
}

void LiveMonitor::apply_settings(const nlohmann::json& json) {
  try {
    set_controls(LiveSettings::from_json(json));  // the session keeps its own copy verbatim
  } catch (const std::exception& error) {
    show_message(tr("Live settings not restored: %1").arg(error.what()), true);
  }
}

void LiveMonitor::emit_settings() {
  if (applying_settings_) return;
  Q_EMIT settings_changed(settings().to_json());
}

void LiveMonitor::set_rig_schedule(std::vector<daq::ExcitationStep> schedule) {
  rig_schedule_ = std::move(schedule);
}

void LiveMonitor::update_source_controls() {
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
  const bool live = acquisition_ != nullptr && running();
  rig_group_->setEnabled(source == 0 || rig_ != nullptr);
  set_button_->setEnabled(rig_ != nullptr && live);
  step_button_->setEnabled(rig_ != nullptr && live);
  replay_group_->setEnabled(replay_ != nullptr && live);
  start_button_->setEnabled(!live);
  stop_button_->setEnabled(live);
  record_button_->setEnabled(live);
  mark_button_->setEnabled(live);
}

void LiveMonitor::show_message(const QString& text, bool error) {
  message_label_->setText(text);
  message_label_->setStyleSheet(error ? QStringLiteral("color: rgb(180,30,20)") : QString());
  Q_EMIT message_shown(text);
}

QString LiveMonitor::message() const { return message_label_->text(); }

QLabel* LiveMonitor::status_label(const QString& key) const {
  for (const auto& [k, label] : status_labels_) {
    if (qs(k) == key) return label;
  }
  return nullptr;
}

QCPGraph* LiveMonitor::edc_graph(const std::string& well) const {
  return well == "positive" ? edc_graphs_[0] : well == "negative" ? edc_graphs_[1] : edc_graphs_[2];
}

// --- running ---------------------------------------------------------------------------------

bool LiveMonitor::start() {
  stop();
  const LiveSettings s = settings();
  std::unique_ptr<daq::SampleSource> source;
  daq::RigSource* rig = nullptr;
  daq::ReplaySource* replay = nullptr;
  daq::NetSource* net = nullptr;
  daq::JackSource* jack = nullptr;
  try {
    // One factory for the CLI and the app (daq/live/source_factory.h).
    daq::SourceOptions o;
    o.what = "source";
    o.positive_well = s.rig_positive_well;
    o.frequency_hz = s.rig_frequency_hz;
    o.speed = s.speed;
    o.schedule = rig_schedule_;
    o.duration_s = rig_duration_s_;
    o.loop = s.replay_loop;
    std::string spec;
    switch (s.source) {
      case LiveSourceKind::Rig:
        spec = "rig";
        break;
      case LiveSourceKind::Replay:
        if (s.replay_path.empty())
          throw InputError("replay: choose a recording to replay (\u2026)");
        spec = "file:" + s.replay_path;
        break;
      case LiveSourceKind::Network:
        spec = "net:127.0.0.1:" + std::to_string(s.port);
        break;
      case LiveSourceKind::Jack:
        if (s.jack_calibration.empty()) {
          throw InputError("JACK: choose the calibration sidecar (base and mass channels)");
        }
        spec = "jack:" + s.jack_base_port + "," + s.jack_mass_port;
        o.jack_server = s.jack_server;
        o.calibration = daq::read_sidecar(s.jack_calibration);
        break;
    }
    source = daq::make_source(spec, o);
    rig = dynamic_cast<daq::RigSource*>(source.get());
    replay = dynamic_cast<daq::ReplaySource*>(source.get());
    net = dynamic_cast<daq::NetSource*>(source.get());
    jack = dynamic_cast<daq::JackSource*>(source.get());
    if (rig != nullptr && rig_schedule_.empty() && s.rig_f0_n > 0) {
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
  timeline_ = LiveTimeline(window_box_->value(), daq::AcquisitionOptions{}.history_s);
  pause_view_button_->setChecked(false);
  replay_pause_button_->setChecked(false);
  event_faults_ = {};
  fault_tracker_.reset();
  throughput_.reset();
  analysis::StreamingSlices::Options rfs = rfs_.options();
  rfs.frequency_hz = frequency_hz();
  rfs_ = analysis::StreamingSlices(rfs);
  events_seen_ = 0;
  levels_shown_ = static_cast<std::size_t>(-1);
  current_shown_.reset();
  event_log_->setRowCount(0);
  std::fill(trace_units_.begin(), trace_units_.end(), std::nullopt);
  std::fill(trace_ranges_.begin(), trace_ranges_.end(), std::nullopt);
  for (QCustomPlot* plot : {stiffness_plot_, damping_plot_, spectrum_plot_}) {
    for (int g = 0; g < plot->graphCount(); ++g) plot->graph(g)->data()->clear();
  }
  if (auto* loop = qobject_cast<QCPCurve*>(loop_plot_->plottable(0))) loop->data()->clear();
  for (int k = 0; k < kTraceCount; ++k) {
    trace_names_[std::size_t(k)]->setText(trace_name(k, layout_));
  }
  std::fill(std::begin(last_part_ms_), std::end(last_part_ms_), -1000);

  show_message(net_ ? tr("Listening on 127.0.0.1:%1 for a sender.").arg(net_->port())
                    : tr("Started: %1.").arg(qs(acquisition_->source().describe())),
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
  stop_recording_button_->setEnabled(true);
  return true;
}

void LiveMonitor::stop_recording() {
  if (!acquisition_) return;
  acquisition_->stop_recording();
  stop_recording_button_->setEnabled(false);
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
  {
    const QSignalBlocker block_f0(f0_box_), block_freq(frequency_box_);
    f0_box_->setValue(f0_n);
    frequency_box_->setValue(frequency_hz);
  }
  emit_settings();
  show_message(tr("Excitation set: f\u2080 = %1 N at %2 Hz.").arg(f0_n).arg(frequency_hz), false);
}

void LiveMonitor::step_excitation() {
  if (!rig_) {
    show_message(tr("Start the virtual rig first."), true);
    return;
  }
  const daq::ExcitationStep now = rig_->excitation();
  set_excitation(now.f0_n + step_box_->value(), now.frequency_hz);
}

void LiveMonitor::set_view_paused(bool paused) {
  if (paused) {
    timeline_.pause();
  } else {
    timeline_.resume();
  }
  {
    const QSignalBlocker block(pause_view_button_);
    pause_view_button_->setChecked(paused);
  }
  sync_scroll_bar();
  refresh_traces();
}

void LiveMonitor::scroll_view_to(double end_s) {
  timeline_.scroll_to(end_s);
  {
    const QSignalBlocker block(pause_view_button_);
    pause_view_button_->setChecked(true);
  }
  sync_scroll_bar();
  refresh_traces();
}

void LiveMonitor::sync_scroll_bar() {
  const TimeWindow range = timeline_.scroll_range();
  const TimeWindow view = timeline_.view();
  const QSignalBlocker block(scroll_bar_);
  scroll_bar_->setRange(static_cast<int>(std::floor(10 * range.start_s)),
                        static_cast<int>(std::ceil(10 * range.end_s)));
  scroll_bar_->setPageStep(std::max(1, static_cast<int>(10 * timeline_.window_s())));
  scroll_bar_->setSingleStep(std::max(1, static_cast<int>(timeline_.window_s())));
  scroll_bar_->setValue(static_cast<int>(std::lround(10 * view.end_s)));
}

double LiveMonitor::frequency_hz() const {
  if (rig_) return rig_->excitation().frequency_hz;
  if (acquisition_) {
    if (layout_ && layout_->excitation && layout_->excitation->frequency_hz) {
      return *layout_->excitation->frequency_hz;
    }
    return 0.0;
  }
  return frequency_box_->value();
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
                     .arg(qs(acquisition_->source().describe())),
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
  const daq::AcquisitionStatus status = acquisition_->status();
  timeline_.advance(status.stream_time_s);
  const TimeWindow window = timeline_.view();
  const int buckets = std::max(200, trace_plot_->width());  // a min–max pair per pixel column
  acquisition_->history(window.start_s, window.end_s, buckets, traces_);
  if (!layout_ && status.layout_known) {  // a network sender's layout arrived
    layout_ = acquisition_->layout();
    for (int k = 0; k < kTraceCount; ++k) {
      trace_names_[std::size_t(k)]->setText(trace_name(k, layout_));
    }
  }
  const std::optional<daq::Sidecar>& layout = layout_;
  const std::vector<double>* series[kTraceCount] = {&traces_.base, &traces_.b_m, &traces_.mass,
                                                    &traces_.z_m, &traces_.force_n};
  QVector<QCPGraphData> data;
  for (int k = 0; k < kTraceCount; ++k) {
    const std::vector<double>& v = *series[k];
    double lo = 0.0, hi = 0.0;
    finite_range(v, lo, hi);
    const double max_abs = lo <= hi ? std::max(std::abs(lo), std::abs(hi)) : 0.0;
    const DisplayUnit unit =
        sticky_display_unit(trace_units_[std::size_t(k)], trace_si_unit(k, layout), max_abs);
    if (!trace_units_[std::size_t(k)] || trace_units_[std::size_t(k)]->symbol != unit.symbol) {
      trace_units_[std::size_t(k)] = unit;
      trace_ranges_[std::size_t(k)].reset();
      trace_rects_[std::size_t(k)]
          ->axis(QCPAxis::atLeft)
          ->setLabel(trace_symbol(k) + " [" + qs(unit.symbol) + "]");
    }
    data.resize(static_cast<qsizetype>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
      data[qsizetype(i)] = QCPGraphData(traces_.t_s[i], unit.to_display(v[i]));
    }
    trace_graphs_[std::size_t(k)]->data()->set(data, true);
    if (lo <= hi) {
      const AxisRange range =
          follow_range(trace_ranges_[std::size_t(k)], unit.to_display(lo), unit.to_display(hi));
      trace_ranges_[std::size_t(k)] = range;
      trace_rects_[std::size_t(k)]->axis(QCPAxis::atLeft)->setRange(range.lo, range.hi);
    }
    trace_rects_[std::size_t(k)]->axis(QCPAxis::atBottom)->setRange(window.start_s, window.end_s);
  }
  if (!timeline_.following()) sync_scroll_bar();
  trace_plot_->replot(QCustomPlot::rpQueuedReplot);
}

bool LiveMonitor::list_jack_ports() {
  try {
    const std::vector<std::string> ports =
        daq::JackSource::capture_ports(jack_server_edit_->text().toStdString());
    for (QComboBox* box : jack_port_boxes_) {
      const QString chosen = box->currentText();
      const QSignalBlocker block(box);
      box->clear();
      for (const std::string& port : ports) box->addItem(qs(port));
      box->setCurrentText(chosen);
    }
    show_message(
        tr("%n capture port(s) on the JACK server.", nullptr, static_cast<int>(ports.size())),
        false);
    return true;
  } catch (const std::exception& error) {
    show_message(tr("Cannot list JACK ports: %1").arg(error.what()), true);
    return false;
  }
}

void LiveMonitor::refresh_status() {
  if (jack_ != nullptr && running()) {
    const std::vector<double> peaks = jack_->peaks();
    for (std::size_t c = 0; c < 2 && c < peaks.size(); ++c) {
      jack_meters_[c]->setValue(static_cast<int>(std::lround(std::min(peaks[c], 100.0))));
    }
  }
  if (!acquisition_) {
    for (const auto& [key, label] : status_labels_) label->setText(qs(key));
    warning_label_->setText(tr("No source running."));
    return;
  }
  const daq::AcquisitionStatus status = acquisition_->status();
  // New events: the log and the fault counts.
  const std::vector<daq::StreamEvent> events = acquisition_->events_since(events_seen_);
  if (!events.empty()) {
    QScrollBar* bar = event_log_->verticalScrollBar();
    const bool at_bottom = bar->value() >= bar->maximum() - 2;
    event_log_->setUpdatesEnabled(false);
    for (const daq::StreamEvent& event : events) {
      event_faults_.add(event);
      const EventRow row = event_row(event);
      const int r = event_log_->rowCount();
      event_log_->insertRow(r);
      const QString cells[3] = {qs(row.time), qs(row.kind), qs(row.text)};
      for (int c = 0; c < 3; ++c) {
        auto* item = new QTableWidgetItem(cells[c]);
        if (c == 2) item->setToolTip(cells[c]);
        if (row.severity == Severity::Fault) item->setBackground(kRed.lighter(170));
        if (row.severity == Severity::Warning) item->setBackground(kAmber.lighter(130));
        event_log_->setItem(r, c, item);
      }
    }
    if (event_log_->rowCount() > kMaxLogRows) {
      const int excess = event_log_->rowCount() - kMaxLogRows;
      for (int i = 0; i < excess; ++i) event_log_->removeRow(0);
    }
    event_log_->setUpdatesEnabled(true);
    events_seen_ += events.size();
    if (at_bottom) event_log_->scrollToBottom();
  }
  const double now_s = 1e-3 * static_cast<double>(clock_->elapsed());
  const FaultCounts faults = event_faults_.merged(status);
  fault_tracker_.update(faults, now_s);
  throughput_.add(now_s, status.samples);
  for (const StatusField& field :
       status_fields(status, faults, fault_tracker_, now_s, throughput_.samples_per_s())) {
    QLabel* label = status_label(qs(field.key));
    if (!label) continue;
    const QString text =
        field.label.empty() ? qs(field.value) : qs(field.label + " " + field.value);
    if (label->text() != text) label->setText(text);
    const int severity = static_cast<int>(field.severity);
    if (label->property("severity").toInt() != severity) {
      label->setProperty("severity", severity);
      label->setStyleSheet(severity_style(field.severity));
    }
    if (label->toolTip() != qs(field.tooltip)) label->setToolTip(qs(field.tooltip));
  }
  stop_recording_button_->setEnabled(status.recording);

  // The level being filled, and what is wrong with it.
  const std::optional<analysis::LevelResult> current = acquisition_->current_level();
  const std::string warning = level_warning(current);
  QString text;
  if (current && current->cycles > 0) {
    text = tr("Level now: f\u2080 = %1 N, %2 well, %3 steady cycles, EDC %4 \u00b1 %5 mJ (3\u03c3)")
               .arg(current->f0_n, 0, 'f', 3)
               .arg(qs(current->well))
               .arg(current->cycles)
               .arg(1e3 * current->edc_mean_j, 0, 'g', 4)
               .arg(3e3 * current->edc_std_j, 0, 'g', 2);
  } else if (!status.edc_message.empty()) {
    text = qs(status.edc_message);
  } else {
    text = tr("No level being filled (ramp, rest or transient).");
  }
  if (!warning.empty()) text += tr("  \u26a0 %1").arg(qs(warning));
  warning_label_->setText(text);
  const int severity = warning.empty() ? 0 : 1;
  if (warning_label_->property("severity").toInt() != severity) {
    warning_label_->setProperty("severity", severity);
    warning_label_->setStyleSheet(
        severity_style(warning.empty() ? Severity::Normal : Severity::Warning));
  }

  if (rig_) {
    const daq::ExcitationStep now = rig_->excitation();
    rig_now_label_->setText(
        tr("f\u2080 = %1 N at %2 Hz").arg(now.f0_n, 0, 'f', 3).arg(now.frequency_hz, 0, 'g', 4));
  }
  if (replay_) {
    const double position = replay_->position_s(), duration = replay_->duration_s();
    seek_label_->setText(tr("%1 / %2 s").arg(position, 0, 'f', 1).arg(duration, 0, 'f', 1));
    if (!seek_slider_->isSliderDown() && duration > 0) {
      const QSignalBlocker block(seek_slider_);
      seek_slider_->setValue(static_cast<int>(1000.0 * position / duration));
    }
  }
}

void LiveMonitor::refresh_analysis() {
  refresh_edc();
  refresh_slices();
  refresh_cycle();
}

void LiveMonitor::refresh_slices() {
  if (!acquisition_) return;
  const daq::AcquisitionStatus status = acquisition_->status();
  if (!status.layout_known || !(status.sample_rate_hz > 0)) return;
  const double rate_hz = status.sample_rate_hz;
  const double nu = frequency_hz();
  if (nu > 0 && std::abs(nu - rfs_.options().frequency_hz) > 1e-9) {
    analysis::StreamingSlices::Options o = rfs_.options();
    o.frequency_hz = nu;
    rfs_ = analysis::StreamingSlices(o);  // a new ν: a new cycle length for the bands
  }
  // Samples one by one over what the slices have not taken yet (the derived traces lag).
  const double now_s = status.stream_time_s;
  const double from_s = std::max(
      {0.0, now_s - kMaxSliceCatchUpS, std::min(rfs_.taken_until_s(), now_s - kAnalysisSpanS)});
  const int samples = static_cast<int>(std::ceil((now_s - from_s) * rate_hz)) + 2;
  acquisition_->history(from_s, now_s, samples, raw_);
  if (raw_.t_s.empty() ||
      rfs_.add(raw_.t_s, raw_.z_m, raw_.z_dot_m_s, raw_.restoring_force_n, rate_hz) == 0)
    return;
  for (auto [plot, points] :
       {std::pair{stiffness_plot_, &rfs_.stiffness()}, std::pair{damping_plot_, &rfs_.damping()}}) {
    QVector<QCPGraphData> wells[2];
    for (const analysis::WellPoint& p : *points) {
      wells[p.positive ? 0 : 1].push_back(QCPGraphData(1e3 * p.x, p.y));  // z in mm, ż in mm/s
    }
    double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
    for (int w = 0; w < 2; ++w) {
      plot->graph(w)->data()->set(wells[w], false);
      show_in_legend(plot->graph(w), !wells[w].isEmpty());
      for (const QCPGraphData& d : wells[w]) {
        x_lo = std::min(x_lo, d.key), x_hi = std::max(x_hi, d.key);
        y_lo = std::min(y_lo, d.value), y_hi = std::max(y_hi, d.value);
      }
    }
    fit_axis(plot->xAxis, x_lo, x_hi);
    fit_axis(plot->yAxis, y_lo, y_hi);
    set_plot_hint(plot, points->empty() ? tr("No samples in the band yet.") : QString());
    plot->replot(QCustomPlot::rpQueuedReplot);
  }
}

void LiveMonitor::refresh_cycle() {
  if (!acquisition_) return;
  const daq::AcquisitionStatus status = acquisition_->status();
  if (!status.layout_known || !(status.sample_rate_hz > 0)) return;
  const double rate_hz = status.sample_rate_hz;
  const double nu = frequency_hz();
  const double now_s = status.stream_time_s;
  const double from_s = std::max(0.0, now_s - kAnalysisSpanS);
  acquisition_->history(from_s, now_s, static_cast<int>(std::ceil((now_s - from_s) * rate_hz)) + 2,
                        raw_);
  if (raw_.t_s.empty()) return;

  // The loop of the newest whole cycle of z.
  if (nu > 0) {
    const analysis::CycleLoop cycle =
        analysis::newest_cycle_loop(raw_.t_s, raw_.z_m, raw_.force_n, nu);
    if (auto* curve = qobject_cast<QCPCurve*>(loop_plot_->plottable(0));
        curve && !cycle.z_m.empty()) {
      QVector<QCPCurveData> data(static_cast<qsizetype>(cycle.z_m.size()));
      for (std::size_t i = 0; i < cycle.z_m.size(); ++i) {
        data[qsizetype(i)] = QCPCurveData(double(i), 1e3 * cycle.z_m[i], cycle.f_n[i]);
      }
      curve->data()->set(data, true);
      const QColor colour = well_colour(cycle.positive ? "positive" : "negative");
      curve->setPen(QPen(colour, 1.5));
      curve->setBrush(QColor(colour.red(), colour.green(), colour.blue(), 40));
      curve->setName(
          tr("t = %1 \u2013 %2 s").arg(cycle.start_s, 0, 'f', 2).arg(cycle.end_s, 0, 'f', 2));
      double lo = 0, hi = 0;
      finite_range(cycle.z_m, lo, hi);
      fit_axis(loop_plot_->xAxis, 1e3 * lo, 1e3 * hi);
      finite_range(cycle.f_n, lo, hi);
      fit_axis(loop_plot_->yAxis, lo, hi);
      set_plot_hint(loop_plot_, QString());
      loop_plot_->replot(QCustomPlot::rpQueuedReplot);
    }
  }

  // The spectrum of z over the newest few seconds.
  const analysis::ZSpectrum spectrum = analysis::z_spectrum(raw_.z_m, rate_hz, nu);
  if (!spectrum.freq_hz.empty()) {
    QVector<QCPGraphData> data;
    data.reserve(static_cast<qsizetype>(spectrum.freq_hz.size()));
    double peak = 0.0;
    for (std::size_t k = 1; k < spectrum.freq_hz.size(); ++k) {  // the mean removed: from bin 1
      data.push_back(QCPGraphData(spectrum.freq_hz[k], std::max(spectrum.amplitude_m[k], 1e-12)));
      peak = std::max(peak, spectrum.amplitude_m[k]);
    }
    spectrum_plot_->graph(0)->data()->set(data, true);
    QVector<QCPGraphData> markers;
    for (std::size_t h = 0; h < spectrum.harmonic_freq_hz.size(); ++h) {
      markers.push_back(QCPGraphData(spectrum.harmonic_freq_hz[h],
                                     std::max(spectrum.harmonic_amplitude_m[h], 1e-12)));
    }
    spectrum_plot_->graph(1)->data()->set(markers, true);
    spectrum_plot_->graph(1)->setName(tr("h\u03bd, \u03bd = %1 Hz").arg(nu, 0, 'g', 4));
    spectrum_plot_->xAxis->setRange(0.0, std::min(0.5 * rate_hz, nu > 0 ? 9.5 * nu : 60.0));
    if (peak > 0) spectrum_plot_->yAxis->setRange(peak * 1e-5, peak * 3.0);
    set_plot_hint(spectrum_plot_, QString());
    spectrum_plot_->replot(QCustomPlot::rpQueuedReplot);
  }
}

void LiveMonitor::refresh_edc() {
  if (!acquisition_) return;
  const std::vector<analysis::LevelResult> levels = acquisition_->levels();
  const double nu = frequency_hz();
  if (nu > 0 && (std::abs(nu - predicted_frequency_hz_) > 1e-9 ||
                 edc_plot_data(levels, std::nullopt).max_f0_n > predicted_top_n_ + 1e-9)) {
    start_prediction(nu);  // a new ν, or levels past the prediction's
  }
  const std::optional<analysis::LevelResult> current = acquisition_->current_level();
  const bool same_current = current.has_value() == current_shown_.has_value() &&
                            (!current || (current->cycles == current_shown_->cycles &&
                                          current->edc_mean_j == current_shown_->edc_mean_j));
  if (levels.size() == levels_shown_ && same_current) return;
  levels_shown_ = levels.size();
  current_shown_ = current;

  const EdcPlotData data = edc_plot_data(levels, current);
  const std::vector<EdcPoint>* series[3] = {&data.positive, &data.negative, &data.other};
  double top = 0.0;
  for (int w = 0; w < 3; ++w) {
    QVector<double> f0, edc, error;
    for (const EdcPoint& p : *series[w]) {
      f0.push_back(p.f0_n);
      edc.push_back(1e3 * p.edc_j);
      error.push_back(1e3 * p.error_j);
      top = std::max(top, 1e3 * (p.edc_j + p.error_j));
    }
    edc_graphs_[w]->setData(f0, edc, true);
    edc_bars_[w]->setData(error);
    show_in_legend(edc_graphs_[w], !f0.isEmpty());
  }
  QVector<double> f0, edc, error;
  if (data.current) {
    f0.push_back(data.current->f0_n);
    edc.push_back(1e3 * data.current->edc_j);
    error.push_back(1e3 * data.current->error_j);
    top = std::max(top, 1e3 * (data.current->edc_j + data.current->error_j));
    const QColor colour = well_colour(data.current_well);
    current_graph_->setPen(QPen(colour.darker(140), 1.5));
  }
  current_graph_->setData(f0, edc, true);
  edc_bars_[3]->setData(error);
  show_in_legend(current_graph_, !f0.isEmpty());
  // The axes hold the measured points and the model up to a little past the levels measured
  // (the whole model before there are any), so that the first levels are not squeezed flat.
  const double x_top = std::max(2.8, data.max_f0_n + 0.1);
  const double model_top = data.max_f0_n > 0 ? 1.25 * data.max_f0_n + 0.1 : x_top;
  for (QCPGraph* model : model_graphs_) {
    for (auto it = model->data()->constBegin(); it != model->data()->constEnd(); ++it) {
      if (it->key <= model_top) top = std::max(top, it->value);
    }
  }
  edc_plot_->xAxis->setRange(0.0, x_top);
  edc_plot_->yAxis->setRange(0.0, top > 0 ? 1.08 * top : 1.0);
  set_plot_hint(edc_plot_, levels.empty() && !data.current
                               ? tr("Levels appear here as the stepped sine runs.")
                               : QString());
  edc_plot_->replot(QCustomPlot::rpQueuedReplot);
}

// --- the model's prediction ------------------------------------------------------------------

void LiveMonitor::set_prediction_model(std::shared_ptr<const analysis::Model> model,
                                       const QString& label) {
  if (!model) return;
  prediction_model_ = std::move(model);
  prediction_label_ = label;
  for (int w = 0; w < 2; ++w) {
    model_graphs_[w]->setName((w == 0 ? tr("z\u208a* ") : tr("z\u208b* ")) + label + tr(", HBM"));
    model_graphs_[w]->data()->clear();
  }
  predicted_frequency_hz_ = 0.0;  // recompute at the next frame
  if (acquisition_) start_prediction(frequency_hz());
}

void LiveMonitor::start_prediction(double frequency_hz) {
  if (!(frequency_hz > 0)) return;
  const double max_f0 =
      acquisition_ ? edc_plot_data(acquisition_->levels(), std::nullopt).max_f0_n : 0.0;
  if (prediction_job_->running()) {
    prediction_again_ = true;
    return;
  }
  auto prediction = std::make_shared<Prediction>();
  prediction->model = prediction_model_;
  prediction->frequency_hz = frequency_hz;
  prediction->levels_n = prediction_levels(max_f0);
  prediction_ = prediction;
  predicted_frequency_hz_ = frequency_hz;
  predicted_top_n_ = prediction->levels_n.back();
  prediction_again_ = false;
  prediction_job_->start([prediction](const ProgressFn&, const CancelToken& cancel) {
    // Harmonic balance of the model, level by level (a sweep up, §4.2), per well: milliseconds
    // each (measured: ~4 ms for 53 levels), so cancellation between wells suffices.
    try {
      for (int w = 0; w < 2 && !cancel.cancelled(); ++w) {
        prediction->wells[w] = analysis::level_response(
            *prediction->model, prediction->frequency_hz, w == 0, prediction->levels_n);
      }
    } catch (const std::exception& error) {
      prediction->error = error.what();
    }
  });
}

void LiveMonitor::on_prediction_finished(bool cancelled) {
  const std::shared_ptr<Prediction> prediction = prediction_;
  if (cancelled || !prediction) return;
  QString message;
  if (!prediction->error.empty()) {
    message = tr("Model prediction failed: %1").arg(qs(prediction->error));
  }
  for (int w = 0; w < 2; ++w) {
    const analysis::LevelResponse& r = prediction->wells[w];
    QVector<double> f0, edc;
    for (std::size_t i = 0; i < r.f0_n.size() && i < r.edc_j.size(); ++i) {
      f0.push_back(r.f0_n[i]);
      edc.push_back(1e3 * r.edc_j[i]);
    }
    model_graphs_[w]->setData(f0, edc, true);
    show_in_legend(model_graphs_[w], !f0.isEmpty());
    if (r.status != JobStatus::Ok && message.isEmpty()) {
      message = tr("Model prediction (%1 well): %2")
                    .arg(w == 0 ? tr("z\u208a*") : tr("z\u208b*"))
                    .arg(qs(r.message));
    }
  }
  levels_shown_ = static_cast<std::size_t>(-1);  // redraw the EDC plot with the model
  if (acquisition_) {
    refresh_edc();
  } else {
    edc_plot_->replot();
  }
  Q_EMIT prediction_finished(message);
  if (prediction_again_) start_prediction(frequency_hz());
}

}  // namespace oscilab::ui

#include "ui/live/live_status_strip.h"

#include <algorithm>
#include <map>
#include <optional>

#include <QElapsedTimer>
#include <QHeaderView>
#include <QLabel>
#include <QScrollBar>
#include <QTableWidget>
#include <QVBoxLayout>

#include "ui/flow_layout.h"
#include "ui/live/live_edc_plot_data.h"
#include "ui/live/live_event_row.h"
#include "ui/live/live_status_fields.h"
#include "ui/qt_text.h"

namespace oscilab::ui {
namespace {

constexpr int kMaxLogRows = 2000;  // the event log keeps the newest rows
const QColor kAmber(255, 196, 70);
const QColor kRed(214, 60, 50);

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

}  // namespace

LiveStatusStrip::LiveStatusStrip(QWidget* parent)
    : QWidget(parent), clock_(std::make_unique<QElapsedTimer>()) {
  clock_->start();
  setObjectName("live_status_strip");

  // The figures in rows that wrap with the strip's width (FlowLayout). Each label is at least as
  // wide as its widest expected text, whatever it shows now, so that a changing figure never
  // changes the page's layout; a longer text widens its label instead of being cut or printed
  // over its neighbour.
  auto* strip = new QWidget;
  strip->setObjectName("status_strip");
  auto* strip_layout = new FlowLayout(strip, 6, 2);
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
      {"errors", "errors 000"},
      {"card", "card 000"}};
  const std::vector<StatusField> fields =
      status_fields({}, {}, fault_tracker_, 0.0, 0.0);  // the keys, in order
  for (const StatusField& field : fields) {
    auto* label = new QLabel;
    label->setObjectName(qtext("status_" + field.key));
    label->setStyleSheet(severity_style(Severity::Normal));
    label->setProperty("severity", 0);
    const auto text = widest.find(field.key);
    // The style's padding (4 px each side) and a margin for bold or wider glyphs.
    label->setMinimumWidth(
        label->fontMetrics().horizontalAdvance(text != widest.end() ? text->second : "0000000") +
        14);
    label->setSizePolicy(QSizePolicy::Minimum, QSizePolicy::Fixed);
    if (field.key == "source") label->setWordWrap(true);  // a long file name takes two lines
    strip_layout->addWidget(label);
    labels_.emplace_back(field.key, label);
  }
  warning_label_ = new QLabel;
  warning_label_->setObjectName("level_warning");
  warning_label_->setStyleSheet(severity_style(Severity::Normal));
  warning_label_->setWordWrap(true);  // a long warning takes a second line, never cut
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(strip);
  layout->addWidget(warning_label_);

  event_log_ = new QTableWidget(0, 3, this);
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
}

LiveStatusStrip::~LiveStatusStrip() = default;

void LiveStatusStrip::reset() {
  event_faults_ = {};
  fault_tracker_.reset();
  throughput_.reset();
  events_seen_ = 0;
  event_log_->setRowCount(0);
}

QLabel* LiveStatusStrip::label(const QString& key) const {
  for (const auto& [k, label] : labels_) {
    if (qtext(k) == key) return label;
  }
  return nullptr;
}

void LiveStatusStrip::show_idle() {
  for (const auto& [key, label] : labels_) label->setText(qtext(key));
  warning_label_->setText(tr("No source running."));
}

void LiveStatusStrip::add_events(const std::vector<daq::StreamEvent>& events) {
  QScrollBar* bar = event_log_->verticalScrollBar();
  const bool at_bottom = bar->value() >= bar->maximum() - 2;
  event_log_->setUpdatesEnabled(false);
  for (const daq::StreamEvent& event : events) {
    event_faults_.add(event);
    const EventRow row = event_row(event);
    const int r = event_log_->rowCount();
    event_log_->insertRow(r);
    const QString cells[3] = {qtext(row.time), qtext(row.kind), qtext(row.text)};
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

void LiveStatusStrip::update(const daq::Acquisition& acquisition,
                             const daq::AcquisitionStatus& status) {
  // New events: the log and the fault counts.
  const std::vector<daq::StreamEvent> events = acquisition.events_since(events_seen_);
  if (!events.empty()) add_events(events);
  const double now_s = 1e-3 * static_cast<double>(clock_->elapsed());
  const FaultCounts faults = event_faults_.merged(status);
  fault_tracker_.update(faults, now_s);
  throughput_.add(now_s, status.samples);
  for (const StatusField& field :
       status_fields(status, faults, fault_tracker_, now_s, throughput_.samples_per_s())) {
    QLabel* label = this->label(qtext(field.key));
    if (!label) continue;
    const QString text =
        field.label.empty() ? qtext(field.value) : qtext(field.label + " " + field.value);
    if (label->text() != text) label->setText(text);
    const int severity = static_cast<int>(field.severity);
    if (label->property("severity").toInt() != severity) {
      label->setProperty("severity", severity);
      label->setStyleSheet(severity_style(field.severity));
    }
    if (label->toolTip() != qtext(field.tooltip)) label->setToolTip(qtext(field.tooltip));
  }

  // The level being filled, and what is wrong with it.
  const std::optional<analysis::LevelResult> current = acquisition.current_level();
  const std::string warning = level_warning(current);
  QString text;
  if (current && current->cycles > 0) {
    text = tr("Level now: f\u2080 = %1 N, %2 well, %3 steady cycles, EDC %4 \u00b1 %5 mJ (3\u03c3)")
               .arg(current->f0_n, 0, 'f', 3)
               .arg(qtext(to_string(current->well)))
               .arg(current->cycles)
               .arg(1e3 * current->edc_mean_j, 0, 'g', 4)
               .arg(3e3 * current->edc_std_j, 0, 'g', 2);
  } else if (!status.edc_message.empty()) {
    text = qtext(status.edc_message);
  } else {
    text = tr("No level being filled (ramp, rest or transient).");
  }
  if (!warning.empty()) text += tr("  \u26a0 %1").arg(qtext(warning));
  warning_label_->setText(text);
  const int severity = warning.empty() ? 0 : 1;
  if (warning_label_->property("severity").toInt() != severity) {
    warning_label_->setProperty("severity", severity);
    warning_label_->setStyleSheet(
        severity_style(warning.empty() ? Severity::Normal : Severity::Warning));
  }
}

}  // namespace oscilab::ui

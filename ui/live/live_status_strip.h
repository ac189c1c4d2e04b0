#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <QString>
#include <QWidget>

#include "daq/live/acquisition.h"
#include "ui/live/live_faults.h"
#include "ui/live/throughput_meter.h"

class QElapsedTimer;
class QLabel;
class QTableWidget;

namespace oscilab::ui {

/// The live monitor's status strip: rows of figures that wrap with its width (live_status_fields.h:
/// rate, stream time, samples, fault counters that turn amber and red as they rise, queue,
/// recording, cycles, latency, alarms), the line about the level being filled with its warning, and
/// the event log whose events it counts as faults. The event log is a separate widget the monitor
/// places (event_log()). Used from the UI thread only.
class LiveStatusStrip : public QWidget {
  Q_OBJECT

 public:
  explicit LiveStatusStrip(QWidget* parent = nullptr);
  ~LiveStatusStrip() override;

  /// A new stream: no events seen, no faults counted, an empty log.
  void reset();
  /// No acquisition: each figure shows its name.
  void show_idle();
  /// Reads the acquisition's new events into the log and the fault counts and shows `status`
  /// and the level being filled.
  void update(const daq::Acquisition& acquisition, const daq::AcquisitionStatus& status);

  /// The value label of a key of status_fields ("samples", "gaps", ...); null for another key.
  QLabel* label(const QString& key) const;
  QLabel* warning_label() const { return warning_label_; }
  QTableWidget* event_log() const { return event_log_; }

 private:
  void add_events(const std::vector<daq::StreamEvent>& events);

  FaultCounts event_faults_;
  FaultTracker fault_tracker_;
  ThroughputMeter throughput_;
  std::size_t events_seen_ = 0;
  std::unique_ptr<QElapsedTimer> clock_;  // wall time for the tracker and the throughput

  std::vector<std::pair<std::string, QLabel*>> labels_;
  QLabel* warning_label_ = nullptr;
  QTableWidget* event_log_ = nullptr;
};

}  // namespace oscilab::ui

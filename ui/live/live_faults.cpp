#include "ui/live/live_faults.h"

#include <algorithm>

namespace oscilab::ui {
namespace {

std::uint64_t data_count(const daq::StreamEvent& event, const char* name, std::uint64_t fallback) {
  const auto it = event.data.find(name);
  if (it == event.data.end() || !it->is_number()) return fallback;
  const double v = it->get<double>();
  return v > 0 ? static_cast<std::uint64_t>(v) : 0;
}

}  // namespace

void FaultCounts::add(const daq::StreamEvent& event) {
  using daq::EventKind;
  const EventKind kind = event.kind;
  if (kind == EventKind::Gap) {
    ++gaps;
    gap_samples += data_count(event, "samples", 0);
  } else if (kind == EventKind::Duplicate) {
    ++duplicates;
  } else if (kind == EventKind::Reordered) {
    ++reordered;
  } else if (kind == EventKind::Late) {
    ++late;
  } else if (kind == EventKind::NonFinite) {
    non_finite_samples += data_count(event, "samples", 1);
  } else if (kind == EventKind::Saturated) {
    saturated_samples += data_count(event, "samples", 1);
  } else if (kind == EventKind::Overflow) {
    // The event carries the source's running total (one event per 100 overflows).
    overflowed_blocks =
        std::max(overflowed_blocks, data_count(event, "blocks", overflowed_blocks + 1));
  } else if (kind == EventKind::Alarm) {
    ++alarms;
  } else if (kind == EventKind::Error || kind == EventKind::MalformedFrame ||
             kind == EventKind::LayoutMismatch) {
    ++errors;
  }
}

FaultCounts FaultCounts::merged(const daq::AcquisitionStatus& s) const {
  FaultCounts m = *this;
  m.gaps = std::max(gaps, s.gaps);
  m.gap_samples = std::max(gap_samples, s.gap_samples);
  m.duplicates = std::max(duplicates, s.duplicates);
  m.reordered = std::max(reordered, s.reordered);
  m.late = std::max(late, s.late);
  m.non_finite_samples = std::max(non_finite_samples, s.non_finite_samples);
  m.saturated_samples = std::max(saturated_samples, s.saturated_samples);
  m.overflowed_blocks = std::max(overflowed_blocks, s.overflowed_blocks);
  m.alarms = std::max(alarms, s.alarms);
  m.errors = std::max(errors, s.network.malformed_frames + s.network.layout_mismatches);
  m.sound_card = std::max(sound_card, s.jack.xruns + s.jack.server_losses +
                                          s.jack.port_disconnections + s.jack.rate_changes);
  return m;
}

std::map<std::string, std::uint64_t> FaultTracker::fault_values(const FaultCounts& c) {
  return {{"gaps", c.gap_samples},
          {"duplicates", c.duplicates},
          {"reordered", c.reordered},
          {"late", c.late},
          {"nan", c.non_finite_samples},
          {"saturated", c.saturated_samples},
          {"overflow", c.overflowed_blocks},
          {"alarms", c.alarms},
          {"errors", c.errors},
          {"card", c.sound_card}};
}

void FaultTracker::update(const FaultCounts& counts, double now_s) {
  for (const auto& [name, value] : fault_values(counts)) {
    std::uint64_t& last = last_[name];
    if (value > last) rose_at_[name] = now_s;
    last = value;
  }
}

Severity FaultTracker::severity(const std::string& name, double now_s) const {
  const auto value = last_.find(name);
  if (value == last_.end() || value->second == 0) return Severity::Normal;
  const auto rose = rose_at_.find(name);
  if (rose != rose_at_.end() && now_s - rose->second < fresh_s_) return Severity::Fault;
  return Severity::Warning;
}

}  // namespace oscilab::ui

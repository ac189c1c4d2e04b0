#include "ui/live/live_status_fields.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/number_text.h"

namespace oscilab::ui {
namespace {

std::string count_text(std::uint64_t n) { return std::to_string(n); }

}  // namespace

std::vector<StatusField> status_fields(const daq::AcquisitionStatus& s, const FaultCounts& faults,
                                       const FaultTracker& tracker, double now_s,
                                       double samples_per_s) {
  std::vector<StatusField> fields;
  const auto add = [&](std::string key, std::string label, std::string value,
                       Severity severity = Severity::Normal, std::string tooltip = {}) {
    fields.push_back(
        {std::move(key), std::move(label), std::move(value), severity, std::move(tooltip)});
  };
  const auto fault = [&](const char* key) { return tracker.severity(key, now_s); };

  const char* state = s.running && !s.finished ? "running" : s.finished ? "ended" : "stopped";
  add("source", "", s.source.empty() ? "no source" : s.source + " (" + state + ")");
  std::string rate = s.sample_rate_hz > 0 ? number_text("%g Hz", s.sample_rate_hz) : "—";
  if (s.sample_rate_hz > 0 && samples_per_s > 0 && s.running && !s.finished) {
    rate += number_text(" \u00d7%.3g", samples_per_s / s.sample_rate_hz);
  }
  add("rate", "rate", rate, Severity::Normal,
      "Sample rate of the stream; \u00d7: samples arriving per second of wall time / rate");
  add("time", "t", number_text("%.1f s", s.stream_time_s), Severity::Normal,
      "Stream time: the sample clock of the newest sample processed");
  add("samples", "samples", count_text(s.samples));
  add("gaps", "gaps", count_text(faults.gap_samples) + " (" + count_text(faults.gaps) + ")",
      fault("gaps"), "Samples that never arrived (number of gaps)");
  add("duplicates", "dup", count_text(faults.duplicates), fault("duplicates"),
      "Blocks that arrived twice (dropped)");
  const Severity reorder_severity = std::max(fault("reordered"), fault("late"));
  add("reordered", "reord",
      count_text(faults.reordered) + (faults.late ? " +" + count_text(faults.late) + " late" : ""),
      reorder_severity, "Blocks put back in order (late: arrived after their gap was closed)");
  add("nan", "NaN", count_text(faults.non_finite_samples), fault("nan"),
      "Non-finite samples (left out of the analysis)");
  add("saturated", "sat", count_text(faults.saturated_samples), fault("saturated"),
      "Samples at or beyond a channel's range");
  add("overflow", "overflow", count_text(faults.overflowed_blocks), fault("overflow"),
      "Blocks the source dropped because the queue was full");
  add("queue", "queue", count_text(s.queue_fill) + "/" + count_text(s.queue_capacity),
      s.queue_capacity > 0 && 4 * s.queue_fill > 3 * s.queue_capacity ? Severity::Warning
                                                                      : Severity::Normal,
      "Blocks waiting between the source and the acquisition thread / capacity");
  const double recorded_s =
      s.sample_rate_hz > 0 ? static_cast<double>(s.recorded_samples) / s.sample_rate_hz : 0.0;
  std::string recording = s.recording              ? number_text("\u25cf %.1f s", recorded_s)
                          : s.recorded_samples > 0 ? number_text("off (%.1f s written)", recorded_s)
                                                   : std::string("off");
  Severity recording_severity = Severity::Normal;
  if (!s.recorder_error.empty()) {
    recording += " error";
    recording_severity = Severity::Fault;
  }
  add("recording", "rec", recording, recording_severity,
      s.recorder_error.empty() ? s.recording_path : s.recorder_error);
  add("cycles", "cycles",
      count_text(static_cast<std::uint64_t>(std::max(0L, s.cycles))) + " (" +
          count_text(static_cast<std::uint64_t>(std::max(0L, s.excluded_cycles))) + " excl.)",
      s.excluded_cycles > 0 ? Severity::Warning : Severity::Normal,
      "Cycles fitted (excluded: touched by a fault)");
  add("levels", "levels", count_text(s.levels), Severity::Normal,
      s.edc_message.empty() ? "Stepped-sine levels finished" : s.edc_message);
  add("latency", "EDC latency",
      s.edc_latency_s > 0 ? number_text("%.0f ms", 1e3 * s.edc_latency_s) : std::string("—"),
      Severity::Normal,
      number_text("Arrival of a cycle's first sample to its EDC; median %.0f ms",
                  1e3 * s.edc_latency_median_s) +
          number_text(", max %.0f ms", 1e3 * s.edc_latency_max_s));
  add("alarms", "alarms", count_text(faults.alarms), fault("alarms"),
      "Alarm limits crossed (|z|, |b| drift, |f|)");
  add("errors", "errors", count_text(faults.errors), fault("errors"),
      "Source errors, malformed frames and refused senders");
  // A sound card's own faults; each is also an event, and what it cost shows as gaps.
  const bool sound_card = s.source.rfind("JACK", 0) == 0;
  add("card", "card",
      sound_card || faults.sound_card > 0 ? count_text(faults.sound_card) : "\u2014", fault("card"),
      "Sound card (JACK) faults: " + count_text(s.jack.xruns) + " xrun(s), " +
          count_text(s.jack.server_losses) + " server loss(es), " +
          count_text(s.jack.port_disconnections) + " port(s) disconnected, " +
          count_text(s.jack.rate_changes) + " rate change(s); " +
          count_text(s.jack.dropped_frames) + " frame(s) dropped, " +
          count_text(s.jack.clipped_samples) + " input sample(s) clipped, " +
          count_text(s.jack.reconnections) + " reconnection(s)");
  return fields;
}

}  // namespace oscilab::ui

#include "ui/live_view_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "analysis/common/input_error.h"
#include "analysis/simulation/stepped_levels.h"

namespace oscilab::ui {
namespace {

constexpr double kMinWindowS = 0.1;
// Fewer samples than this make no spectrum worth drawing (a few cycles at 9 Hz, 512 Hz).

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string count_text(std::uint64_t n) { return std::to_string(n); }

// A double field of `json`, if present: a number, else InputError naming it.
std::optional<double> number_field(const nlohmann::json& json, const char* name,
                                   const std::string& path) {
  if (!json.contains(name) || json.at(name).is_null()) return std::nullopt;
  const nlohmann::json& value = json.at(name);
  if (!value.is_number()) {
    throw InputError(path + "." + name + ": expected a number, got " + value.dump());
  }
  return value.get<double>();
}

void require(bool ok, const std::string& field, double value, const char* why) {
  if (!ok) throw InputError(field + ": " + format("%g", value) + " (" + why + ")");
}

std::uint64_t data_count(const daq::StreamEvent& event, const char* name, std::uint64_t fallback) {
  const auto it = event.data.find(name);
  if (it == event.data.end() || !it->is_number()) return fallback;
  const double v = it->get<double>();
  return v > 0 ? static_cast<std::uint64_t>(v) : 0;
}

}  // namespace

std::string to_string(LiveSourceKind kind) {
  switch (kind) {
    case LiveSourceKind::Replay:
      return "replay";
    case LiveSourceKind::Network:
      return "network";
    case LiveSourceKind::Jack:
      return "jack";
    default:
      return "rig";
  }
}

// --- settings --------------------------------------------------------------------------------

nlohmann::json LiveSettings::to_json() const {
  const auto optional = [](const std::optional<double>& v) -> nlohmann::json {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  return {{"source", to_string(source)},
          {"replay_path", replay_path},
          {"replay_loop", replay_loop},
          {"port", port},
          {"jack",
           {{"server", jack_server},
            {"base_port", jack_base_port},
            {"mass_port", jack_mass_port},
            {"calibration", jack_calibration}}},
          {"rig",
           {{"f0_n", rig_f0_n},
            {"frequency_hz", rig_frequency_hz},
            {"step_n", rig_step_n},
            {"well", rig_positive_well ? "positive" : "negative"}}},
          {"speed", speed},
          {"window_s", window_s},
          {"alarms",
           {{"max_abs_z_m", optional(alarms.max_abs_z_m)},
            {"max_abs_base_m", optional(alarms.max_abs_base_m)},
            {"max_abs_force_n", optional(alarms.max_abs_force_n)}}}};
}

LiveSettings LiveSettings::from_json(const nlohmann::json& json) {
  LiveSettings s;
  if (json.is_null()) return s;
  if (!json.is_object()) throw InputError("live: expected an object, got " + json.dump());
  if (json.contains("source")) {
    const nlohmann::json& v = json.at("source");
    const std::string name = v.is_string() ? v.get<std::string>() : v.dump();
    if (name == "rig") {
      s.source = LiveSourceKind::Rig;
    } else if (name == "replay") {
      s.source = LiveSourceKind::Replay;
    } else if (name == "network") {
      s.source = LiveSourceKind::Network;
    } else if (name == "jack") {
      s.source = LiveSourceKind::Jack;
    } else {
      throw InputError("live.source: unknown source \"" + name +
                       "\" (rig, replay, network or jack)");
    }
  }
  if (json.contains("replay_path")) {
    if (!json.at("replay_path").is_string()) {
      throw InputError("live.replay_path: expected a string, got " + json.at("replay_path").dump());
    }
    s.replay_path = json.at("replay_path").get<std::string>();
  }
  if (json.contains("replay_loop")) {
    if (!json.at("replay_loop").is_boolean()) {
      throw InputError("live.replay_loop: expected true or false, got " +
                       json.at("replay_loop").dump());
    }
    s.replay_loop = json.at("replay_loop").get<bool>();
  }
  if (const auto port = number_field(json, "port", "live")) {
    require(*port >= 0 && *port <= 65535 && *port == std::floor(*port), "live.port", *port,
            "a TCP port, 0 to 65535");
    s.port = static_cast<int>(*port);
  }
  if (json.contains("jack")) {
    const nlohmann::json& jack = json.at("jack");
    if (!jack.is_object()) throw InputError("live.jack: expected an object, got " + jack.dump());
    const std::pair<const char*, std::string*> fields[] = {{"server", &s.jack_server},
                                                           {"base_port", &s.jack_base_port},
                                                           {"mass_port", &s.jack_mass_port},
                                                           {"calibration", &s.jack_calibration}};
    for (const auto& [name, field] : fields) {
      if (!jack.contains(name)) continue;
      if (!jack.at(name).is_string()) {
        throw InputError(std::string("live.jack.") + name + ": expected a string, got " +
                         jack.at(name).dump());
      }
      *field = jack.at(name).get<std::string>();
    }
  }
  if (json.contains("rig")) {
    const nlohmann::json& rig = json.at("rig");
    if (!rig.is_object()) throw InputError("live.rig: expected an object, got " + rig.dump());
    if (const auto v = number_field(rig, "f0_n", "live.rig")) {
      require(*v >= 0, "live.rig.f0_n", *v, "must be >= 0");
      s.rig_f0_n = *v;
    }
    if (const auto v = number_field(rig, "frequency_hz", "live.rig")) {
      require(*v > 0, "live.rig.frequency_hz", *v, "must be positive");
      s.rig_frequency_hz = *v;
    }
    if (const auto v = number_field(rig, "step_n", "live.rig")) {
      require(*v > 0, "live.rig.step_n", *v, "must be positive");
      s.rig_step_n = *v;
    }
    if (rig.contains("well")) {
      const nlohmann::json& well = rig.at("well");
      if (well != "positive" && well != "negative") {
        throw InputError("live.rig.well: expected \"positive\" or \"negative\", got " +
                         well.dump());
      }
      s.rig_positive_well = well == "positive";
    }
  }
  if (const auto v = number_field(json, "speed", "live")) {
    require(*v >= 0, "live.speed", *v, "must be >= 0; 0: as fast as possible");
    s.speed = *v;
  }
  if (const auto v = number_field(json, "window_s", "live")) {
    require(*v >= kMinWindowS && *v <= 600.0, "live.window_s", *v, "0.1 to 600 s");
    s.window_s = *v;
  }
  if (json.contains("alarms")) {
    const nlohmann::json& alarms = json.at("alarms");
    if (!alarms.is_object()) {
      throw InputError("live.alarms: expected an object, got " + alarms.dump());
    }
    const std::pair<const char*, std::optional<double>*> limits[] = {
        {"max_abs_z_m", &s.alarms.max_abs_z_m},
        {"max_abs_base_m", &s.alarms.max_abs_base_m},
        {"max_abs_force_n", &s.alarms.max_abs_force_n}};
    for (const auto& [name, limit] : limits) {
      if (const auto v = number_field(alarms, name, "live.alarms")) {
        require(*v > 0, std::string("live.alarms.") + name, *v, "must be positive, or null: off");
        *limit = *v;
      }
    }
  }
  return s;
}

std::vector<daq::ExcitationStep> stepped_schedule(double from_n, double to_n, double step_n,
                                                  double hold_s, double lead_in_s,
                                                  double frequency_hz) {
  if (!(from_n > 0)) throw InputError("stepped sine: needs a first level above 0 N");
  return daq::rig_schedule(analysis::stepped_levels(from_n, step_n, to_n, "stepped sine"), hold_s,
                           lead_in_s, frequency_hz);
}

// --- time window -----------------------------------------------------------------------------

LiveTimeline::LiveTimeline(double window_s, double history_s)
    : window_s_(window_s), history_s_(std::max(history_s, kMinWindowS)) {
  set_window_s(window_s);
}

void LiveTimeline::set_window_s(double window_s) {
  window_s_ = std::isfinite(window_s) ? std::clamp(window_s, kMinWindowS, history_s_) : 10.0;
}

void LiveTimeline::advance(double stream_time_s) {
  if (std::isfinite(stream_time_s)) now_s_ = stream_time_s;
}

void LiveTimeline::pause() {
  if (!following_) return;
  paused_end_s_ = view().end_s;
  following_ = false;
}

void LiveTimeline::resume() { following_ = true; }

TimeWindow LiveTimeline::scroll_range() const {
  const double end = std::max(now_s_, window_s_);
  const double oldest = std::max(0.0, now_s_ - history_s_);
  return {std::min(end, oldest + window_s_), end};
}

void LiveTimeline::scroll_to(double end_s) {
  following_ = false;
  const TimeWindow range = scroll_range();
  paused_end_s_ =
      std::isfinite(end_s) ? std::clamp(end_s, range.start_s, range.end_s) : range.end_s;
}

TimeWindow LiveTimeline::view() const {
  const TimeWindow range = scroll_range();
  const double end = following_ ? range.end_s : std::max(paused_end_s_, range.start_s);
  return {end - window_s_, end};
}

// --- faults ----------------------------------------------------------------------------------

void FaultCounts::add(const daq::StreamEvent& event) {
  const std::string& kind = event.kind;
  if (kind == "gap") {
    ++gaps;
    gap_samples += data_count(event, "samples", 0);
  } else if (kind == "duplicate") {
    ++duplicates;
  } else if (kind == "reordered") {
    ++reordered;
  } else if (kind == "late") {
    ++late;
  } else if (kind == "non-finite") {
    non_finite_samples += data_count(event, "samples", 1);
  } else if (kind == "saturated") {
    saturated_samples += data_count(event, "samples", 1);
  } else if (kind == "overflow") {
    // The event carries the source's running total (one event per 100 overflows).
    overflowed_blocks =
        std::max(overflowed_blocks, data_count(event, "blocks", overflowed_blocks + 1));
  } else if (kind == "alarm") {
    ++alarms;
  } else if (kind == "error" || kind == "malformed-frame" || kind == "layout-mismatch") {
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
  m.errors = std::max(errors, s.malformed_frames + s.layout_mismatches);
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
          {"errors", c.errors}};
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

void ThroughputMeter::add(double wall_s, std::uint64_t samples) {
  if (!readings_.empty() && samples < readings_.back().second) readings_.clear();  // restarted
  readings_.emplace_back(wall_s, samples);
  while (readings_.size() > 2 && wall_s - readings_[1].first >= span_s_) readings_.pop_front();
}

double ThroughputMeter::samples_per_s() const {
  if (readings_.size() < 2) return 0.0;
  const double dt = readings_.back().first - readings_.front().first;
  if (!(dt >= 0.1)) return 0.0;
  return static_cast<double>(readings_.back().second - readings_.front().second) / dt;
}

// --- status and events -----------------------------------------------------------------------

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
  std::string rate = s.sample_rate_hz > 0 ? format("%g Hz", s.sample_rate_hz) : "—";
  if (s.sample_rate_hz > 0 && samples_per_s > 0 && s.running && !s.finished) {
    rate += format(" \u00d7%.3g", samples_per_s / s.sample_rate_hz);
  }
  add("rate", "rate", rate, Severity::Normal,
      "Sample rate of the stream; \u00d7: samples arriving per second of wall time / rate");
  add("time", "t", format("%.1f s", s.stream_time_s), Severity::Normal,
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
  std::string recording = s.recording              ? format("\u25cf %.1f s", recorded_s)
                          : s.recorded_samples > 0 ? format("off (%.1f s written)", recorded_s)
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
      s.edc_latency_s > 0 ? format("%.0f ms", 1e3 * s.edc_latency_s) : std::string("—"),
      Severity::Normal,
      format("Arrival of a cycle's first sample to its EDC; median %.0f ms",
             1e3 * s.edc_latency_median_s) +
          format(", max %.0f ms", 1e3 * s.edc_latency_max_s));
  add("alarms", "alarms", count_text(faults.alarms), fault("alarms"),
      "Alarm limits crossed (|z|, |b| drift, |f|)");
  add("errors", "errors", count_text(faults.errors), fault("errors"),
      "Source errors, malformed frames and refused senders");
  return fields;
}

EventRow event_row(const daq::StreamEvent& event) {
  EventRow row;
  row.time = std::isfinite(event.t_s) ? format("%.3f s", event.t_s) : "\u2014";
  row.kind = event.kind;
  row.text = !event.text.empty()  ? event.text
             : event.data.empty() ? std::string()
                                  : event.data.dump();
  const std::string& k = event.kind;
  if (k == "gap" || k == "overflow" || k == "non-finite" || k == "saturated" || k == "alarm" ||
      k == "error" || k == "malformed-frame" || k == "layout-mismatch" || k == "late") {
    row.severity = Severity::Fault;
  } else if (k == "duplicate" || k == "reordered" || k == "discontinuity" || k == "disconnected") {
    row.severity = Severity::Warning;
  }
  return row;
}

// --- EDC -------------------------------------------------------------------------------------

EdcPlotData edc_plot_data(const std::vector<analysis::LevelResult>& levels,
                          const std::optional<analysis::LevelResult>& current) {
  EdcPlotData data;
  const auto point = [&](const analysis::LevelResult& level) {
    data.max_f0_n = std::max(data.max_f0_n, level.f0_n);
    return EdcPoint{level.f0_n, level.edc_mean_j, 3.0 * level.edc_std_j, level.cycles,
                    level.flags()};
  };
  for (const analysis::LevelResult& level : levels) {
    auto& series = level.well == "positive"   ? data.positive
                   : level.well == "negative" ? data.negative
                                              : data.other;
    series.push_back(point(level));
  }
  if (current && current->cycles > 0) {
    data.current = point(*current);
    data.current_well = current->well;
  }
  return data;
}

std::vector<double> prediction_levels(double max_measured_f0_n) {
  constexpr double kFirst = 0.1, kStep = 0.05, kPaperTop = 2.7;  // §3.2: 0.2 → 2.7 N
  const double top =
      std::max(kPaperTop, std::isfinite(max_measured_f0_n) ? max_measured_f0_n + 0.1 : kPaperTop);
  const auto n = static_cast<int>(std::ceil((top - kFirst) / kStep - 1e-9)) + 1;
  std::vector<double> levels;
  for (int i = 0; i < n; ++i) levels.push_back(kFirst + kStep * i);
  return levels;
}

std::string level_warning(const std::optional<analysis::LevelResult>& current) {
  if (!current || current->cycles == 0) return {};
  std::string text;
  if (!current->period1) text = "not period-1 (sub-harmonic or non-periodic motion, Fig. 17)";
  if (current->cross_well) text += std::string(text.empty() ? "" : "; ") + "crosses wells";
  return text;
}

// --- display ---------------------------------------------------------------------------------

DisplayUnit sticky_display_unit(const std::optional<DisplayUnit>& current,
                                const std::string& si_unit, double max_abs) {
  if (current && std::isfinite(max_abs) && max_abs > 0) {
    const double reading = current->to_display(max_abs);
    if (reading >= 0.5 && reading < 2000.0) return *current;
  }
  if (current && !(max_abs > 0)) return *current;  // no data: keep what is shown
  return choose_display_unit(si_unit, max_abs);
}

AxisRange follow_range(std::optional<AxisRange> current, double data_lo, double data_hi) {
  if (!std::isfinite(data_lo) || !std::isfinite(data_hi) || data_hi < data_lo) {
    return current.value_or(AxisRange{});
  }
  double span = data_hi - data_lo;
  if (span <= 0) span = std::max(std::abs(data_hi), 1e-12) * 0.2;
  const AxisRange fitted{data_lo - 0.1 * span, data_hi + 0.1 * span};
  if (!current) return fitted;
  const bool holds = current->lo <= data_lo && current->hi >= data_hi;
  const bool too_wide = (data_hi - data_lo) < 0.4 * (current->hi - current->lo);
  if (holds && !too_wide) return *current;
  return fitted;
}

}  // namespace oscilab::ui

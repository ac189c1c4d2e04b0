#include "daq/sources/stream_event.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "analysis/common/json_number.h"

namespace oscilab::daq {

namespace {

constexpr std::pair<EventKind, const char*> kNames[] = {
    {EventKind::Level, "level"},
    {EventKind::Mark, "mark"},
    {EventKind::Gap, "gap"},
    {EventKind::Duplicate, "duplicate"},
    {EventKind::Reordered, "reordered"},
    {EventKind::Late, "late"},
    {EventKind::Discontinuity, "discontinuity"},
    {EventKind::Invalid, "invalid"},
    {EventKind::Clipped, "clipped"},
    {EventKind::NonFinite, "non-finite"},
    {EventKind::Saturated, "saturated"},
    {EventKind::Overflow, "overflow"},
    {EventKind::Connected, "connected"},
    {EventKind::Disconnected, "disconnected"},
    {EventKind::LayoutMismatch, "layout-mismatch"},
    {EventKind::MalformedFrame, "malformed-frame"},
    {EventKind::Xrun, "xrun"},
    {EventKind::ServerShutdown, "server-shutdown"},
    {EventKind::RateChanged, "rate-changed"},
    {EventKind::PortDisconnected, "port-disconnected"},
    {EventKind::PortConnected, "port-connected"},
    {EventKind::Reconnected, "reconnected"},
    {EventKind::Alarm, "alarm"},
    {EventKind::Warning, "warning"},
    {EventKind::Start, "start"},
    {EventKind::Stop, "stop"},
    {EventKind::RecordingStarted, "recording-started"},
    {EventKind::RecordingStopped, "recording-stopped"},
    {EventKind::SourceEnded, "source-ended"},
    {EventKind::Error, "error"},
};

}  // namespace

const char* to_string(EventKind kind) {
  for (const auto& [k, name] : kNames) {
    if (k == kind) return name;
  }
  return "other";
}

EventKind event_kind_from_string(std::string_view name) {
  for (const auto& [k, known] : kNames) {
    if (name == known) return k;
  }
  return EventKind::Other;
}

std::string StreamEvent::kind_name() const {
  return kind == EventKind::Other ? other_kind : std::string(to_string(kind));
}

nlohmann::json StreamEvent::to_json() const {
  nlohmann::json out;
  out["t_s"] = finite_or_null(t_s);
  out["kind"] = kind_name();
  if (!text.empty()) out["text"] = text;
  if (!data.empty()) out["data"] = data;
  out["wall"] = wall.empty() ? utc_now_iso8601() : wall;
  return out;
}

std::string utc_now_iso8601() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[96];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                static_cast<int>(millis));
  return text;
}

std::string stream_event_problem(const StreamEvent& event, double sample_rate_hz) {
  const bool acted_on = event.kind == EventKind::Level || event.kind == EventKind::Invalid ||
                        event.kind == EventKind::Clipped || event.kind == EventKind::Discontinuity;
  if (!acted_on) return "";
  const std::string kind = to_string(event.kind);
  char text[200];
  const auto problem = [&](const char* key, const char* rule, double value) {
    std::snprintf(text, sizeof text, "%s event: %s %g %s", kind.c_str(), key, value, rule);
    return std::string(text);
  };
  if (!std::isnan(event.t_s) && !(event.t_s >= 0.0 && event.t_s <= kMaxStreamTimeS)) {
    return problem("t_s", "is not a stream time in [0, 1e9] s", event.t_s);
  }
  for (const char* key :
       {"steady_from_s", "steady_to_s", "from_s", "to_s", "f0_n", "frequency_hz"}) {
    const auto it = event.data.find(key);
    if (it == event.data.end()) continue;
    if (!it->is_number()) return kind + " event: " + key + " is not a number: " + it->dump();
    const double value = it->get<double>();
    const std::string name = key;
    if (name == "f0_n") {
      if (!(value >= 0.0) || !std::isfinite(value)) {
        return problem(key, "N is not a finite amplitude >= 0", value);
      }
    } else if (name == "frequency_hz") {
      if (!(value > 0.0 && value < 0.5 * sample_rate_hz)) {
        std::snprintf(text, sizeof text,
                      "%s event: frequency_hz %g is not in (0, %g) Hz (the Nyquist "
                      "frequency of the %g Hz stream)",
                      kind.c_str(), value, 0.5 * sample_rate_hz, sample_rate_hz);
        return text;
      }
    } else if (!(value >= 0.0 && value <= kMaxStreamTimeS)) {
      return problem(key, "is not a stream time in [0, 1e9] s", value);
    }
  }
  // A steady window that ends before it starts holds no cycle: said, not taken as a level.
  const auto from = event.data.find("steady_from_s");
  const auto to = event.data.find("steady_to_s");
  if (event.kind == EventKind::Level && from != event.data.end() && to != event.data.end() &&
      to->get<double>() < from->get<double>()) {
    std::snprintf(text, sizeof text,
                  "level event: the steady window [%g, %g) s ends before it starts",
                  from->get<double>(), to->get<double>());
    return text;
  }
  return "";
}

}  // namespace oscilab::daq

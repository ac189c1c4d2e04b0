#include "daq/live/stream_event.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

namespace oscilab::daq {

nlohmann::json StreamEvent::to_json() const {
  nlohmann::json out;
  out["t_s"] = std::isfinite(t_s) ? nlohmann::json(t_s) : nlohmann::json(nullptr);
  out["kind"] = kind;
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

}  // namespace oscilab::daq

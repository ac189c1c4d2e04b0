#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace oscilab::daq {

/// Something that happened in a live stream, for the status display and the event log (one JSON
/// object per line in `<stem>.events.jsonl`). `kind` is one of:
///   level            the excitation was set (data: f0_n, frequency_hz, ramp_s)
///   mark             an operator's mark (text)
///   gap              blocks never arrived (data: samples, from_s, to_s)
///   duplicate        a block arrived twice and was dropped (data: sequence)
///   reordered        a block arrived out of order and was put back in place (data: sequence)
///   late             a block arrived after its gap was closed and was dropped (data: sequence)
///   non-finite       NaN or Inf samples (data: channel, samples, from_s, to_s)
///   saturated        samples at or beyond a channel's range (data: channel, samples, ...)
///   overflow         the queue was full: the source dropped blocks (data: blocks)
///   connected, disconnected, layout-mismatch, malformed-frame   network source
///   alarm            a limit was crossed (text)
///   start, stop, recording-started, recording-stopped, source-ended, error
/// `t_s` is stream time (sample clock), NaN where it has none; `wall` ISO-8601 UTC.
struct StreamEvent {
  StreamEvent() = default;
  StreamEvent(double t_s_, std::string kind_, std::string text_ = {},
              nlohmann::json data_ = nlohmann::json::object())
      : t_s(t_s_), kind(std::move(kind_)), text(std::move(text_)), data(std::move(data_)) {}

  double t_s = 0.0;
  std::string kind;
  std::string text;
  nlohmann::json data = nlohmann::json::object();
  std::string wall;  // set when the event is logged

  nlohmann::json to_json() const;
};

/// The current UTC time as ISO 8601 with milliseconds, e.g. "2026-11-24T09:12:03.123Z".
std::string utc_now_iso8601();

}  // namespace oscilab::daq

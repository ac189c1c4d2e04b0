#pragma once

#include <limits>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace oscilab::daq {

/// What a stream event says happened. Its name (to_string) is what the event log and the stream
/// protocol carry:
///   level            the excitation was set (data: f0_n, frequency_hz, ramp_s)
///   mark             an operator's mark (text)
///   gap              blocks never arrived (data: samples, from_s, to_s)
///   duplicate        a block arrived twice and was dropped (data: sequence)
///   reordered        a block arrived out of order and was put back in place (data: sequence)
///   late             a block arrived after its gap was closed and was dropped (data: sequence)
///   discontinuity    the samples on either side of it are not one motion (a seek, a clock jump)
///   invalid          a replayed recording's own invalid stretch (data: from_s, to_s)
///   clipped          input at the interface's full scale before resampling (data: from_s, to_s)
///   non-finite       NaN or Inf samples (data: channel, samples, from_s, to_s)
///   saturated        samples at or beyond a channel's range (data: channel, samples, ...)
///   overflow         the queue was full: the source dropped blocks (data: blocks)
///   connected, disconnected, layout-mismatch, malformed-frame   network and JACK sources
///   xrun, server-shutdown, rate-changed, port-disconnected, port-connected, reconnected   JACK
///   alarm            a limit was crossed (text)
///   warning          a set-up the analysis can do, but not well (text)
///   start, stop, recording-started, recording-stopped, source-ended, error
/// `other` is a kind a network sender named that this program does not know; the event keeps
/// the sender's name for it.
enum class EventKind {
  Level,
  Mark,
  Gap,
  Duplicate,
  Reordered,
  Late,
  Discontinuity,
  Invalid,
  Clipped,
  NonFinite,
  Saturated,
  Overflow,
  Connected,
  Disconnected,
  LayoutMismatch,
  MalformedFrame,
  Xrun,
  ServerShutdown,
  RateChanged,
  PortDisconnected,
  PortConnected,
  Reconnected,
  Alarm,
  Warning,
  Start,
  Stop,
  RecordingStarted,
  RecordingStopped,
  SourceEnded,
  Error,
  Other
};

/// The kind's name in the event log and the stream protocol, e.g. "non-finite".
const char* to_string(EventKind kind);
/// The kind of a name; Other for a name no kind has.
EventKind event_kind_from_string(std::string_view name);

/// Something that happened in a live stream, for the status display and the event log (one JSON
/// object per line in `<stem>.events.jsonl`). `t_s` is stream time (sample clock), NaN where it
/// has none; `wall` ISO-8601 UTC.
/// The t_s of an event that has no stream time (a connection, a server's state).
inline constexpr double kNoTime = std::numeric_limits<double>::quiet_NaN();

struct StreamEvent {
  StreamEvent() = default;
  StreamEvent(double t_s_, EventKind kind_, std::string text_ = {},
              nlohmann::json data_ = nlohmann::json::object())
      : t_s(t_s_), kind(kind_), text(std::move(text_)), data(std::move(data_)) {}

  double t_s = 0.0;
  EventKind kind = EventKind::Mark;
  std::string other_kind;  // the sender's name of a kind this program does not know (Other)
  std::string text;
  nlohmann::json data = nlohmann::json::object();
  std::string wall;  // set when the event is logged

  /// to_string(kind), or the sender's own name for an Other.
  std::string kind_name() const;
  nlohmann::json to_json() const;
};

/// The current UTC time as ISO 8601 with milliseconds, e.g. "2026-11-24T09:12:03.123Z".
std::string utc_now_iso8601();

/// The longest stream time an event may name, s: 10^9 s is 31 years, so that a time times any
/// sample rate stays an exact sample index; a larger one is a sender's mistake, not a clock.
inline constexpr double kMaxStreamTimeS = 1e9;

/// Why an event the acquisition acts on cannot be trusted at a stream of `sample_rate_hz` (empty
/// when it can): a `level` whose f0_n is not a finite number >= 0 or whose frequency_hz is not a
/// finite number in (0, sample_rate_hz / 2) (beyond Nyquist no cycle can be resolved); a `level`,
/// `invalid`, `clipped` or `discontinuity` whose t_s, steady_from_s, steady_to_s, from_s or to_s
/// is not a number in [0, kMaxStreamTimeS] (t_s may be NaN: no time); a `level` whose
/// steady_to_s comes before its steady_from_s. Other kinds are only logged and always pass.
std::string stream_event_problem(const StreamEvent& event, double sample_rate_hz);

}  // namespace oscilab::daq

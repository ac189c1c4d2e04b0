#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

struct _jack_client;  // libjack's jack_client_t (jack/types.h), kept out of this header

namespace oscilab::daq {

/// "the default JACK server" or "JACK server \"NAME\"", for messages.
std::string jack_server_text(const std::string& server);

/// Opens a JACK client on a server (never starting one), with libjack's own printing silenced
/// (callers report in their own words). Null when no such server runs or it refused the client.
_jack_client* open_jack_client(const std::string& client_name, const std::string& server);

/// A server's shutdown as a client's shutdown callback reports it, and when (steady clock).
/// Written by libjack's thread in the callback, read by the client's owner.
class JackShutdown {
 public:
  void clear() { at_ns_.store(0, std::memory_order_release); }
  void report();
  bool happened() const { return at_ns_.load(std::memory_order_acquire) != 0; }
  /// The steady-clock time of the report (meaningful when happened()).
  std::chrono::steady_clock::time_point at() const;

 private:
  std::atomic<std::int64_t> at_ns_{0};  // 0: no shutdown reported
};

/// How long libjack's thread that reported a shutdown may still run inside libjack, holding its
/// locks, after the callback returns. Measured in microseconds; this leaves a wide margin.
inline constexpr std::chrono::milliseconds kJackShutdownSettle{200};

/// Closes a client (null: nothing). After its server shut down, first waits until
/// kJackShutdownSettle has passed since the shutdown was reported: jack_client_close kills the
/// client's notification thread (pthread_cancel), and libjack 1.9.21 (Debian 12) lets it be
/// killed while it holds a lock it takes around the shutdown; that lock then stays held and
/// every later jack_client_open in the process waits on it for ever (seen as a source that
/// never reconnects and a stop() that never returns). The thread is done by then and dies
/// harmlessly. A client whose server shut down is never deactivated: the deactivation talks to
/// a server that is gone and can crash inside libjack.
void close_jack_client(_jack_client* client, const JackShutdown& shutdown);

}  // namespace oscilab::daq

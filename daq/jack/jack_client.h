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
/// (callers report in their own words). Null when no such server runs, it refused the client or
/// JACK's metadata database is damaged (damaged_jack_metadata), with `why` saying which in words.
_jack_client* open_jack_client(const std::string& client_name, const std::string& server,
                               std::string& why);

/// libjack's metadata folder: "jack_db-UID" in its server directory (/dev/shm).
std::string jack_metadata_folder();

/// What is wrong with JACK's metadata database (a Berkeley DB environment libjack opens in
/// /dev/shm/jack_db-UID on every jack_client_open), or "" when nothing is seen: a region file
/// left empty by a JACK program killed while creating it makes libdb fault inside
/// jack_client_open (SIGBUS, which would end the process). The words say what to do.
std::string damaged_jack_metadata(const std::string& folder = jack_metadata_folder());

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

/// How long to let libjack's thread that reported a shutdown finish before its client is
/// closed. The thread should end right after the callback returns; 200 ms is a margin for a
/// loaded machine, chosen, not measured.
inline constexpr std::chrono::milliseconds kJackShutdownSettle{200};

/// Closes a client (null: nothing). After its server shut down, first waits until
/// kJackShutdownSettle has passed since the shutdown was reported: jack_client_close kills the
/// client's notification thread (pthread_cancel), that thread takes a lock around its socket
/// reads and writes, and in libjack 1.9.21 (Debian 12) a kill while it holds the lock leaves it
/// held, so that every later jack_client_open in the process waits on it for ever (seen here as
/// a source that never reconnected and a stop() that never returned). A client whose server shut
/// down is not deactivated: the deactivation talks to a server that is gone and can crash inside
/// libjack.
void close_jack_client(_jack_client* client, const JackShutdown& shutdown);

}  // namespace oscilab::daq

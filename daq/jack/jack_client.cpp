#include "daq/jack/jack_client.h"

#include <jack/jack.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <thread>

namespace oscilab::daq {
namespace {

// libjack prints its errors (no server, ...) on stderr itself; the callers report them as
// one InputError or event instead.
void quiet(const char*) {}

std::int64_t steady_ns(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

}  // namespace

std::string jack_server_text(const std::string& server) {
  return server.empty() ? "the default JACK server" : "JACK server \"" + server + "\"";
}

std::string jack_metadata_folder() {
  // libjack's "%s/jack_db-%d" of its server directory and the user's id.
  return "/dev/shm/jack_db-" + std::to_string(::getuid());
}

std::string damaged_jack_metadata(const std::string& folder) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    std::error_code size_error;
    if (name.rfind("__db.", 0) == 0 && entry.is_regular_file(size_error) &&
        entry.file_size(size_error) == 0 && !size_error) {
      return "JACK's metadata database " + folder + " is damaged (" + name +
             " is empty, as a JACK program killed while opening it leaves it): remove that "
             "folder while no JACK program runs";
    }
  }
  return "";
}

jack_client_t* open_jack_client(const std::string& client_name, const std::string& server,
                                std::string& why) {
  why = damaged_jack_metadata();
  if (!why.empty()) return nullptr;
  static std::once_flag once;
  std::call_once(once, [] {
    jack_set_error_function(quiet);
    jack_set_info_function(quiet);
  });
  jack_status_t status{};
  jack_client_t* client =
      server.empty()
          ? jack_client_open(client_name.c_str(), JackNoStartServer, &status)
          : jack_client_open(client_name.c_str(),
                             static_cast<jack_options_t>(JackNoStartServer | JackServerName),
                             &status, server.c_str());
  if (client == nullptr) {
    why = jack_server_text(server) + " is not running (or refused the client \"" + client_name +
          "\")";
  }
  return client;
}

void JackShutdown::report() {
  // Never 0 (which means "none"), whatever the clock's epoch.
  at_ns_.store(std::max<std::int64_t>(steady_ns(std::chrono::steady_clock::now()), 1),
               std::memory_order_release);
}

std::chrono::steady_clock::time_point JackShutdown::at() const {
  return std::chrono::steady_clock::time_point(
      std::chrono::nanoseconds(at_ns_.load(std::memory_order_acquire)));
}

void close_jack_client(jack_client_t* client, const JackShutdown& shutdown) {
  if (client == nullptr) return;
  if (shutdown.happened()) {
    std::this_thread::sleep_until(shutdown.at() + kJackShutdownSettle);
  } else {
    jack_deactivate(client);
  }
  jack_client_close(client);
}

}  // namespace oscilab::daq

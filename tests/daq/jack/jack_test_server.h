#pragma once

// Test fixtures for the JACK source: a real jackd with the dummy backend (no sound hardware) and
// a test client in the test process that plays signals into its output ports.

#include <fcntl.h>
#include <jack/jack.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "daq/jack/jack_client.h"

namespace oscilab::daq::testing {

/// `jackd --no-realtime -n NAME -d dummy -r RATE -p PERIOD`, up until a client can open on it;
/// stopped (SIGTERM, then SIGKILL) at destruction. A server that does not come up within 10 s
/// throws std::runtime_error with jackd's own output, so the test fails with the reason (nothing
/// is skipped).
///
/// Names: "oscilab-test-<slot>-<n>", n counting this process's servers and the slot one that no
/// other running test process holds (a lock file, released when the process ends). A server
/// killed with SIGKILL (as the tests of a lost server do) keeps its entry in JACK's registry of 8
/// servers until a server of the same name starts again; with a name of its own per process, a
/// machine that had run the tests a few times refused every new server ("Too many servers
/// already active"). Names from a small set reclaim those entries on later runs, and the slot
/// keeps two test processes that run at once (ctest -j) off each other's servers.
class JackTestServer {
 public:
  explicit JackTestServer(int rate_hz = 48000, int period = 256)
      : rate_hz_(rate_hz), period_(period) {
    // libjack reports a server not up yet on stderr; the probe below expects that.
    jack_set_error_function(+[](const char*) {});
    jack_set_info_function(+[](const char*) {});
    static std::atomic<int> counter{0};
    name_ = "oscilab-test-" + std::to_string(process_slot()) + "-" + std::to_string(counter++);
    log_ = (std::filesystem::temp_directory_path() / (name_ + ".log")).string();
    start();
  }
  ~JackTestServer() {
    stop(SIGTERM);
    std::filesystem::remove(log_);
    // A server killed with SIGKILL leaves its clients' semaphores behind: this server's only.
    std::error_code ignored;
    for (const auto& entry : std::filesystem::directory_iterator("/dev/shm", ignored)) {
      const std::string file = entry.path().filename().string();
      if (file.rfind("jack_sem.", 0) == 0 && file.find("_" + name_ + "_") != std::string::npos) {
        std::filesystem::remove(entry.path(), ignored);
      }
    }
  }
  JackTestServer(const JackTestServer&) = delete;
  JackTestServer& operator=(const JackTestServer&) = delete;

  const std::string& name() const { return name_; }
  int rate_hz() const { return rate_hz_; }
  /// The rate of the next start() (a server that comes back at another rate).
  void set_rate_hz(int rate_hz) { rate_hz_ = rate_hz; }

  void start() {
    // A metadata database with an empty region file (a server or client killed while opening it,
    // as these tests do) makes every later client refuse: on a test machine it is removed, and
    // the next server makes a new one.
    if (!daq::damaged_jack_metadata().empty()) {
      std::error_code ignored;
      std::filesystem::remove_all(daq::jack_metadata_folder(), ignored);
    }
    const std::string rate = std::to_string(rate_hz_), period = std::to_string(period_);
    std::vector<std::string> args = {
        "/usr/bin/jackd", "--no-realtime", "-n", name_, "-d", "dummy", "-r", rate, "-p", period};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("cannot start /usr/bin/jackd: fork failed");
    if (pid_ == 0) {
      // The server ends with the test process, even when a test crashes (SIGTERM: it then
      // unregisters itself; a server killed otherwise keeps one of JACK's 8 server slots until a
      // server of the same name starts again).
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      const int log = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      ::dup2(log, STDOUT_FILENO);
      ::dup2(log, STDERR_FILENO);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
      jack_status_t status{};
      if (jack_client_t* probe = jack_client_open(
              "probe", static_cast<jack_options_t>(JackNoStartServer | JackServerName), &status,
              name_.c_str())) {
        jack_client_close(probe);
        return;
      }
      int exit_status = 0;
      if (::waitpid(pid_, &exit_status, WNOHANG) == pid_) {
        pid_ = -1;
        throw std::runtime_error("jackd " + name_ + " exited at start: " + log_text());
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    stop(SIGKILL);
    throw std::runtime_error("jackd " + name_ +
                             " did not accept a client within 10 s: " + log_text());
  }

  /// Stops the server with `signal` and waits for it (SIGKILL after 5 s).
  void stop(int signal) {
    if (pid_ <= 0) return;
    ::kill(pid_, signal);
    for (int i = 0; i < 500; ++i) {
      if (::waitpid(pid_, nullptr, WNOHANG) == pid_) {
        pid_ = -1;
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  std::string log_text() const {
    std::ifstream in(log_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  /// The first of 16 slots whose lock file this process could lock; it keeps the lock (and the
  /// file descriptor) until it exits.
  static int process_slot() {
    static const int slot = [] {
      constexpr int kSlots = 16;
      for (int k = 0; k < kSlots; ++k) {
        const std::string path = (std::filesystem::temp_directory_path() /
                                  ("oscilab-jack-test-" + std::to_string(k) + ".lock"))
                                     .string();
        const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
        if (fd < 0) continue;
        if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return k;
        ::close(fd);
      }
      throw std::runtime_error("jack test server: all 16 slots are held by running tests");
    }();
    return slot;
  }

  int rate_hz_, period_;
  std::string name_, log_;
  pid_t pid_ = -1;
};

/// A JACK client of the test that plays into `channels` output ports ("<client>:out_<c>"):
/// silence until play(), then either a buffer (interleaved, the server's rate) once, or sines
/// A sin(2π f t + φ) referenced to the server's frame clock (t = frame / rate), so that a test can
/// say what any frame held. stall() makes one process cycle sleep (an xrun).
class JackTestPlayer {
 public:
  struct Sine {
    double amplitude = 0.5, frequency_hz = 9.0, phase_rad = 0.0;
  };

  JackTestPlayer(const std::string& server, int channels, const std::string& name = "player")
      : channels_(channels) {
    jack_status_t status{};
    client_ = jack_client_open(name.c_str(),
                               static_cast<jack_options_t>(JackNoStartServer | JackServerName),
                               &status, server.c_str());
    if (client_ == nullptr) throw std::runtime_error("player: no server " + server);
    for (int c = 0; c < channels; ++c) {
      ports_.push_back(jack_port_register(client_, ("out_" + std::to_string(c)).c_str(),
                                          JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput, 0));
    }
    rate_hz_ = jack_get_sample_rate(client_);
    out_.assign(static_cast<std::size_t>(channels), nullptr);
    jack_set_process_callback(client_, &JackTestPlayer::process_callback, this);
    jack_on_info_shutdown(
        client_,
        +[](jack_status_t, const char*, void* arg) {
          static_cast<JackTestPlayer*>(arg)->gone_.store(true);
        },
        this);
    jack_activate(client_);
  }
  ~JackTestPlayer() { close(); }
  JackTestPlayer(const JackTestPlayer&) = delete;
  JackTestPlayer& operator=(const JackTestPlayer&) = delete;

  void close() {
    if (client_ == nullptr) return;
    // A client whose server died is left as it is: libjack 1.9.21 can crash closing the second
    // client of a process after its server was killed (the source under test closes its own).
    if (!gone_.load()) {
      jack_deactivate(client_);
      jack_client_close(client_);
    }
    client_ = nullptr;
  }
  std::string port(int c) const { return jack_port_name(ports_[static_cast<std::size_t>(c)]); }
  jack_client_t* client() const { return client_; }

  /// Plays `interleaved` once from the next cycle on (then silence); done() after its last frame.
  void play(std::vector<float> interleaved) {
    buffer_ = std::move(interleaved);
    position_ = 0;
    mode_.store(kBuffer, std::memory_order_release);
  }
  void play_sines(std::vector<Sine> sines) {
    sines_ = std::move(sines);
    mode_.store(kSines, std::memory_order_release);
  }
  /// The server shut down (its shutdown callback ran).
  bool gone() const { return gone_.load(); }
  bool done() const { return done_.load(std::memory_order_acquire); }
  std::uint64_t frames_played() const { return played_.load(std::memory_order_acquire); }
  void stall(std::chrono::milliseconds ms) { stall_ms_.store(static_cast<int>(ms.count())); }
  void set_freewheel(bool on) { jack_set_freewheel(client_, on ? 1 : 0); }

 private:
  static constexpr int kSilence = 0, kBuffer = 1, kSines = 2;

  static int process_callback(jack_nframes_t frames, void* arg) {
    return static_cast<JackTestPlayer*>(arg)->process(frames);
  }
  int process(jack_nframes_t frames) {
    if (const int ms = stall_ms_.exchange(0); ms > 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    }
    std::vector<float*>& out = out_;  // sized once: the callback does not allocate
    for (int c = 0; c < channels_; ++c) {
      out[static_cast<std::size_t>(c)] =
          static_cast<float*>(jack_port_get_buffer(ports_[static_cast<std::size_t>(c)], frames));
    }
    const int mode = mode_.load(std::memory_order_acquire);
    const jack_nframes_t frame_time = jack_last_frame_time(client_);
    for (jack_nframes_t f = 0; f < frames; ++f) {
      for (int c = 0; c < channels_; ++c) {
        float value = 0.0f;
        if (mode == kBuffer && position_ < buffer_.size()) {
          value = buffer_[position_ + static_cast<std::size_t>(c)];
        } else if (mode == kSines) {
          const Sine& s = sines_[static_cast<std::size_t>(c)];
          // The frame clock as an exact integer, its phase reduced before the sine.
          const auto frame = static_cast<std::uint64_t>(frame_time + f);
          const double cycles =
              std::fmod(static_cast<double>(frame) * s.frequency_hz / rate_hz_, 1.0);
          value = static_cast<float>(s.amplitude *
                                     std::sin(2.0 * std::numbers::pi * cycles + s.phase_rad));
        }
        out[static_cast<std::size_t>(c)][f] = value;
      }
      if (mode == kBuffer && position_ < buffer_.size()) {
        position_ += static_cast<std::size_t>(channels_);
        played_.fetch_add(1, std::memory_order_relaxed);
        if (position_ >= buffer_.size()) done_.store(true, std::memory_order_release);
      } else if (mode == kSines) {
        played_.fetch_add(1, std::memory_order_relaxed);
      }
    }
    return 0;
  }

  int channels_;
  jack_client_t* client_ = nullptr;
  std::vector<jack_port_t*> ports_;
  std::vector<float*> out_;
  double rate_hz_ = 48000.0;
  std::atomic<int> mode_{kSilence};
  std::vector<float> buffer_;
  std::size_t position_ = 0;
  std::vector<Sine> sines_;
  std::atomic<bool> done_{false};
  std::atomic<std::uint64_t> played_{0};
  std::atomic<int> stall_ms_{0};
  std::atomic<bool> gone_{false};  // the server shut down
};

}  // namespace oscilab::daq::testing

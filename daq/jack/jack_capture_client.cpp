#include "daq/jack/jack_capture_client.h"

#include <jack/jack.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

// JACK port short names: the channel's name with what JACK treats specially replaced.
std::string port_short_name(const std::string& channel) {
  std::string out = "in_" + channel;
  for (char& c : out) {
    if (c == ':' || static_cast<unsigned char>(c) < 0x20) c = '_';
  }
  return out.substr(0, 200);
}

int process_callback(jack_nframes_t frames, void* arg) {
  return static_cast<JackCaptureClient*>(arg)->process(frames);
}
void shutdown_callback(jack_status_t, const char*, void* arg) {
  static_cast<JackCaptureClient*>(arg)->on_shutdown();
}
int xrun_callback(void* arg) {
  static_cast<JackCaptureClient*>(arg)->on_xrun();
  return 0;
}
int rate_callback(jack_nframes_t rate, void* arg) {
  static_cast<JackCaptureClient*>(arg)->on_rate(rate);
  return 0;
}
void connect_callback(jack_port_id_t, jack_port_id_t, int, void* arg) {
  static_cast<JackCaptureClient*>(arg)->on_connections_changed();
}
void freewheel_callback(int starting, void* arg) {
  static_cast<JackCaptureClient*>(arg)->on_freewheel(starting != 0);
}

}  // namespace

void JackCaptureClient::on_xrun() {
  xrun_frame_.store(jack_frame_time(client_), std::memory_order_relaxed);
  xrun_count_.fetch_add(1, std::memory_order_release);
}

void JackCaptureClient::on_rate(std::uint32_t rate) {
  if (rate_hz_ > 0 && static_cast<double>(rate) != rate_hz_) {
    changed_rate_.store(rate, std::memory_order_release);
  }
}

// The real-time part: copies, interleaved, into preallocated slots. No lock, no allocation, no
// system call (jack_port_get_buffer, jack_port_connected and jack_last_frame_time read the
// server's shared memory). Freewheeling is not real time: then a full ring waits for room.
int JackCaptureClient::process(std::uint32_t frames) {
  // Being deactivated: the server unplugs the ports, which is no fault of the stream.
  if (closing_.load(std::memory_order_acquire)) return 0;
  const jack_nframes_t frame_time = jack_last_frame_time(client_);
  const std::size_t channel_count = channels();
  std::uint32_t disconnected = 0;
  for (std::size_t c = 0; c < channel_count; ++c) {
    buffers_[c] = static_cast<float*>(jack_port_get_buffer(ports_[c], frames));
    if (jack_port_connected(ports_[c]) == 0) disconnected |= 1u << c;
  }
  std::uint32_t done = 0;
  while (done < frames) {
    FrameSlot* slot = ring_.begin_push();
    if (slot == nullptr) {
      if (freewheeling_.load(std::memory_order_acquire) &&
          !closing_.load(std::memory_order_acquire)) {
        std::this_thread::sleep_for(std::chrono::microseconds(100));
        continue;
      }
      dropped_.fetch_add(frames - done, std::memory_order_relaxed);
      return 0;
    }
    const std::uint32_t n =
        std::min<std::uint32_t>(frames - done, static_cast<std::uint32_t>(ring_.slot_frames()));
    slot->frame_time = frame_time + done;
    slot->frames = n;
    slot->disconnected = disconnected;
    float* to = slot->data.data();
    for (std::uint32_t f = 0; f < n; ++f) {
      for (std::size_t c = 0; c < channel_count; ++c) *to++ = buffers_[c][done + f];
    }
    ring_.end_push();
    done += n;
  }
  return 0;
}

std::string JackCaptureClient::open() {
  const std::string server = jack_server_text(options_.server);
  std::string why;
  client_ = open_jack_client(options_.client_name, options_.server, why);
  if (client_ == nullptr) return why;
  for (const std::string& name : options_.capture_ports) {
    jack_port_t* port = jack_port_by_name(client_, name.c_str());
    if (port == nullptr) {
      close();
      return "port \"" + name + "\" does not exist on " + server;
    }
    if ((jack_port_flags(port) & JackPortIsOutput) == 0 ||
        std::string(jack_port_type(port)) != JACK_DEFAULT_AUDIO_TYPE) {
      close();
      return "port \"" + name + "\" is not an audio output (a capture port) of " + server;
    }
  }
  ports_.clear();
  for (const std::string& channel : options_.channel_names) {
    jack_port_t* port = jack_port_register(client_, port_short_name(channel).c_str(),
                                           JACK_DEFAULT_AUDIO_TYPE, JackPortIsInput, 0);
    if (port == nullptr) {
      close();
      return "cannot register port \"" + port_short_name(channel) + "\" on " + server;
    }
    ports_.push_back(port);
  }
  rate_hz_ = jack_get_sample_rate(client_);
  period_ = jack_get_buffer_size(client_);
  // Everything the callback touches is allocated here, before activation.
  const std::size_t slot_frames = std::max<std::uint32_t>(period_, 64);
  const auto slots = static_cast<std::size_t>(
      std::ceil(options_.ring_s * rate_hz_ / static_cast<double>(slot_frames)) + 2);
  ring_.allocate(slots, slot_frames, channels());
  buffers_.assign(channels(), nullptr);
  return "";
}

std::string JackCaptureClient::activate() {
  shutdown_.clear();
  closing_.store(false);
  changed_rate_.store(0);
  freewheeling_.store(false);
  jack_set_process_callback(client_, process_callback, this);
  jack_on_info_shutdown(client_, shutdown_callback, this);
  jack_set_xrun_callback(client_, xrun_callback, this);
  jack_set_sample_rate_callback(client_, rate_callback, this);
  jack_set_port_connect_callback(client_, connect_callback, this);
  jack_set_freewheel_callback(client_, freewheel_callback, this);
  if (jack_activate(client_) != 0) {
    close();
    return "cannot activate the client on " + jack_server_text(options_.server);
  }
  connect_ports();
  return "";
}

void JackCaptureClient::deactivate() {
  closing_.store(true, std::memory_order_release);
  // A server that shut down (or was killed) took the client's activation with it: libjack's
  // jack_deactivate then talks to a server that is gone and can crash inside libjack (seen
  // under AddressSanitizer after a SIGKILL). close_jack_client alone releases the client.
  if (client_ != nullptr && !shutdown_.happened()) jack_deactivate(client_);
}

void JackCaptureClient::close() {
  if (client_ != nullptr) {
    closing_.store(true, std::memory_order_release);
    close_jack_client(client_, shutdown_);
    client_ = nullptr;
  }
  ports_.clear();
}

void JackCaptureClient::connect_ports() {
  for (std::size_t c = 0; c < channels(); ++c) {
    if (jack_port_connected_to(ports_[c], options_.capture_ports[c].c_str()) != 0) continue;
    const int result =
        jack_connect(client_, options_.capture_ports[c].c_str(), jack_port_name(ports_[c]));
    (void)result;  // EEXIST or a port gone: the period's connection state tells
  }
  last_connect_try_ = std::chrono::steady_clock::now();
}

std::vector<std::string> JackCaptureClient::capture_ports(const std::string& server) {
  std::string why;
  jack_client_t* client = open_jack_client("oscilab-ports", server, why);
  if (client == nullptr) throw InputError(why);
  std::vector<std::string> names;
  if (const char** ports =
          jack_get_ports(client, nullptr, JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput)) {
    for (const char** p = ports; *p != nullptr; ++p) names.emplace_back(*p);
    jack_free(ports);
  }
  close_jack_client(client, JackShutdown{});
  return names;
}

}  // namespace oscilab::daq

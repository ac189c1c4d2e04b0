#include "daq/drive/jack_drive_client.h"

#include <jack/jack.h>

#include <algorithm>
#include <cmath>

#include "analysis/common/input_error.h"
#include "daq/jack/jack_client.h"

namespace oscilab::daq {
namespace {

int drive_process_callback(jack_nframes_t frames, void* arg) {
  return static_cast<JackDriveClient*>(arg)->process(frames);
}
void drive_shutdown_callback(jack_status_t, const char*, void* arg) {
  static_cast<JackDriveClient*>(arg)->on_shutdown();
}

// "" or why `name` is not a port of the server with audio flowing in the stated direction.
std::string check_port(jack_client_t* client, const std::string& name, unsigned long flag,
                       const char* what, const std::string& server) {
  jack_port_t* port = jack_port_by_name(client, name.c_str());
  if (port == nullptr) return "port \"" + name + "\" does not exist on " + server;
  if ((jack_port_flags(port) & flag) == 0 ||
      std::string(jack_port_type(port)) != JACK_DEFAULT_AUDIO_TYPE) {
    return "port \"" + name + "\" is not " + what + " of " + server;
  }
  return "";
}

}  // namespace

void JackDriveClient::EventQueue::drive_event(const DriveEvent& event) noexcept {
  TimedDriveEvent timed{event, owner_.period_frame_time_ + owner_.period_offset_};
  if (!owner_.events_.push(timed)) owner_.lost_events_.fetch_add(1, std::memory_order_relaxed);
}

std::string JackDriveClient::port_name(const std::string& short_name) const {
  if (client_ == nullptr) return options_.client_name + ":" + short_name;
  return std::string(jack_get_client_name(client_)) + ":" + short_name;
}

// The real-time part. Commands first, then the inputs' connections (a lost input aborts before
// any of this period's drive is written), then the controller sample by sample.
int JackDriveClient::process(std::uint32_t frames) {
  auto* drive = static_cast<float*>(jack_port_get_buffer(drive_out_, frames));
  if (closing_.load(std::memory_order_acquire)) {
    for (std::uint32_t f = 0; f < frames; ++f) drive[f] = 0.0f;
    return 0;
  }
  const auto* acceleration =
      static_cast<const float*>(jack_port_get_buffer(acceleration_in_, frames));
  const auto* position = static_cast<const float*>(jack_port_get_buffer(position_in_, frames));
  period_frame_time_ = jack_last_frame_time(client_);
  period_offset_ = 0;
  Command command;
  while (commands_.pop(command)) {
    switch (command.kind) {
      case CommandKind::Level:
        controller_->set_level(command.amplitude_m_s2, command.frequency_hz);
        break;
      case CommandKind::RampDown:
        controller_->stop();
        break;
      case CommandKind::Rearm:
        controller_->rearm();
        break;
    }
  }
  if (jack_port_connected(acceleration_in_) == 0 || jack_port_connected(position_in_) == 0) {
    controller_->input_lost();
  }
  if (options_.capture_s > 0.0) copy_to_capture(acceleration, position, frames);
  const double acceleration_scale = options_.acceleration_scale_m_s2;
  const double position_scale = options_.position_scale_m;
  for (std::uint32_t f = 0; f < frames; ++f) {
    period_offset_ = f;
    drive[f] = static_cast<float>(
        controller_->step(acceleration[f] * acceleration_scale, position[f] * position_scale));
  }
  state_.store(static_cast<int>(controller_->state()), std::memory_order_relaxed);
  abort_.store(static_cast<int>(controller_->abort_reason()), std::memory_order_relaxed);
  target_m_s2_.store(controller_->target_m_s2(), std::memory_order_relaxed);
  frequency_hz_.store(controller_->frequency_hz(), std::memory_order_relaxed);
  measured_m_s2_.store(controller_->measured_m_s2(), std::memory_order_relaxed);
  drive_fs_.store(controller_->drive_fs(), std::memory_order_relaxed);
  cycles_to_target_.store(controller_->cycles_to_target(), std::memory_order_relaxed);
  samples_.store(controller_->samples(), std::memory_order_release);
  return 0;
}

void JackDriveClient::copy_to_capture(const float* acceleration, const float* position,
                                      std::uint32_t frames) {
  std::uint32_t done = 0;
  while (done < frames) {
    FrameSlot* slot = capture_.begin_push();
    if (slot == nullptr) {
      capture_dropped_.fetch_add(frames - done, std::memory_order_relaxed);
      return;
    }
    const std::uint32_t n =
        std::min<std::uint32_t>(frames - done, static_cast<std::uint32_t>(capture_.slot_frames()));
    slot->frame_time = static_cast<std::uint32_t>(controller_->samples() + done);
    slot->frames = n;
    slot->disconnected = 0;
    float* to = slot->data.data();
    for (std::uint32_t f = done; f < done + n; ++f) {
      *to++ = acceleration[f];
      *to++ = position[f];
    }
    capture_.end_push();
    done += n;
  }
}

std::string JackDriveClient::start() {
  const std::string server = jack_server_text(options_.server);
  if (!std::isfinite(options_.acceleration_scale_m_s2) || options_.acceleration_scale_m_s2 <= 0 ||
      !std::isfinite(options_.position_scale_m) || options_.position_scale_m <= 0) {
    return "drive: the input ports' scales must be positive and finite";
  }
  std::string why;
  client_ = open_jack_client(options_.client_name, options_.server, why);
  if (client_ == nullptr) return why;
  why = check_port(client_, options_.acceleration_port, JackPortIsOutput, "a capture port", server);
  if (why.empty()) {
    why = check_port(client_, options_.position_port, JackPortIsOutput, "a capture port", server);
  }
  if (why.empty() && !options_.drive_port.empty()) {
    why = check_port(client_, options_.drive_port, JackPortIsInput, "a playback port", server);
  }
  if (!why.empty()) {
    stop();
    return why;
  }
  drive_out_ = jack_port_register(client_, "drive", JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput, 0);
  acceleration_in_ =
      jack_port_register(client_, "acceleration", JACK_DEFAULT_AUDIO_TYPE, JackPortIsInput, 0);
  position_in_ =
      jack_port_register(client_, "position", JACK_DEFAULT_AUDIO_TYPE, JackPortIsInput, 0);
  if (drive_out_ == nullptr || acceleration_in_ == nullptr || position_in_ == nullptr) {
    stop();
    return "cannot register the drive's ports on " + server;
  }
  rate_hz_ = jack_get_sample_rate(client_);
  period_ = jack_get_buffer_size(client_);
  if (options_.capture_s > 0.0) {
    if (!std::isfinite(options_.capture_s) || options_.capture_s > 600.0) {
      stop();
      return "drive: the capture ring must hold 0 to 600 s";
    }
    const std::size_t slot_frames = std::max<std::uint32_t>(period_, 64);
    capture_.allocate(static_cast<std::size_t>(std::ceil(options_.capture_s * rate_hz_ /
                                                         static_cast<double>(slot_frames))) +
                          2,
                      slot_frames, 2);
  }
  SineControllerOptions controller = options_.controller;
  controller.sample_rate_hz = rate_hz_;
  try {
    controller_ = std::make_unique<SineController>(controller, &event_sink_);
  } catch (const InputError& error) {
    stop();
    return error.what();
  }
  shutdown_.clear();
  closing_.store(false);
  jack_set_process_callback(client_, drive_process_callback, this);
  jack_on_info_shutdown(client_, drive_shutdown_callback, this);
  if (jack_activate(client_) != 0) {
    stop();
    return "cannot activate the drive on " + server;
  }
  const std::string own_acceleration = port_name("acceleration");
  const std::string own_position = port_name("position");
  if (jack_connect(client_, options_.acceleration_port.c_str(), own_acceleration.c_str()) != 0 ||
      jack_connect(client_, options_.position_port.c_str(), own_position.c_str()) != 0) {
    stop();
    return "cannot connect the drive's inputs to \"" + options_.acceleration_port + "\" and \"" +
           options_.position_port + "\" on " + server;
  }
  if (!options_.drive_port.empty() &&
      jack_connect(client_, port_name("drive").c_str(), options_.drive_port.c_str()) != 0) {
    stop();
    return "cannot connect the drive to \"" + options_.drive_port + "\" on " + server;
  }
  return "";
}

void JackDriveClient::stop() {
  if (client_ == nullptr) return;
  closing_.store(true, std::memory_order_release);
  close_jack_client(client_, shutdown_);
  client_ = nullptr;
  drive_out_ = acceleration_in_ = position_in_ = nullptr;
}

std::string JackDriveClient::send(const Command& command) {
  if (client_ == nullptr || controller_ == nullptr) return "drive: not started";
  if (!commands_.push(command)) return "drive: too many commands waiting for the server";
  return "";
}

std::string JackDriveClient::set_level(double amplitude_m_s2, double frequency_hz) {
  if (!std::isfinite(amplitude_m_s2) || amplitude_m_s2 < 0.0) {
    return "drive level: the amplitude must be zero or positive";
  }
  if (!std::isfinite(frequency_hz) || frequency_hz <= 0.0 || frequency_hz > rate_hz_ / 8.0) {
    return "drive level: the frequency must be positive and at most an eighth of the server's " +
           std::to_string(static_cast<long>(rate_hz_)) + " Hz";
  }
  if (const Status now = status(); now.state == DriveState::Aborted) {
    return std::string("drive: aborted (") + drive_abort_name(now.abort) + "): rearm it first";
  }
  return send({CommandKind::Level, amplitude_m_s2, frequency_hz});
}

std::string JackDriveClient::ramp_down() { return send({CommandKind::RampDown, 0.0, 0.0}); }
std::string JackDriveClient::rearm() { return send({CommandKind::Rearm, 0.0, 0.0}); }

JackDriveClient::Status JackDriveClient::status() const {
  Status status;
  status.samples = samples_.load(std::memory_order_acquire);
  status.state = static_cast<DriveState>(state_.load(std::memory_order_relaxed));
  status.abort = static_cast<DriveAbort>(abort_.load(std::memory_order_relaxed));
  status.target_m_s2 = target_m_s2_.load(std::memory_order_relaxed);
  status.frequency_hz = frequency_hz_.load(std::memory_order_relaxed);
  status.measured_m_s2 = measured_m_s2_.load(std::memory_order_relaxed);
  status.drive_fs = drive_fs_.load(std::memory_order_relaxed);
  status.cycles_to_target = cycles_to_target_.load(std::memory_order_relaxed);
  return status;
}

std::vector<TimedDriveEvent> JackDriveClient::take_events() {
  std::vector<TimedDriveEvent> out;
  TimedDriveEvent event;
  while (events_.pop(event)) out.push_back(event);
  return out;
}

}  // namespace oscilab::daq

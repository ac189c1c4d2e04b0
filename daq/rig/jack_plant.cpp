#include "daq/rig/jack_plant.h"

#include <jack/jack.h>

#include <cmath>

#include "analysis/common/input_error.h"
#include "daq/jack/jack_client.h"

namespace oscilab::daq {
namespace {

int plant_process_callback(jack_nframes_t frames, void* arg) {
  return static_cast<JackPlant*>(arg)->process(frames);
}
void plant_shutdown_callback(jack_status_t, const char*, void* arg) {
  static_cast<JackPlant*>(arg)->on_shutdown();
}

}  // namespace

JackPlant::JackPlant(const analysis::Model& model, Options options)
    : model_(model), options_(std::move(options)) {
  if (const std::string why = options_.shaker.validate(); !why.empty()) {
    throw InputError("plant: shaker " + why);
  }
  if (!std::isfinite(options_.acceleration_scale_m_s2) || options_.acceleration_scale_m_s2 <= 0 ||
      !std::isfinite(options_.position_scale_m) || options_.position_scale_m <= 0) {
    throw InputError("plant: the ports' scales must be positive and finite");
  }
  model_.well(options_.positive_well);  // throws when the model has no such well
}

JackPlant::~JackPlant() { stop(); }

std::string JackPlant::port_name(const std::string& short_name) const {
  if (client_ == nullptr) return options_.client_name + ":" + short_name;
  return std::string(jack_get_client_name(client_)) + ":" + short_name;
}

// The real-time part: one plant step per frame, the drive held over it.
int JackPlant::process(std::uint32_t frames) {
  const auto* drive = static_cast<const float*>(jack_port_get_buffer(drive_port_, frames));
  auto* acceleration = static_cast<float*>(jack_port_get_buffer(acceleration_port_, frames));
  auto* position = static_cast<float*>(jack_port_get_buffer(position_port_, frames));
  for (std::uint32_t f = 0; f < frames; ++f) {
    const SensorChain::Reading reading = plant_->step(drive[f]);
    acceleration[f] = static_cast<float>(reading.base_acc_m_s2 / options_.acceleration_scale_m_s2);
    position[f] = static_cast<float>(reading.y_m / options_.position_scale_m);
  }
  z_m_.store(plant_->z_m(), std::memory_order_release);
  frames_.fetch_add(frames, std::memory_order_acq_rel);
  return 0;
}

std::string JackPlant::start() {
  const std::string server = jack_server_text(options_.server);
  std::string why;
  client_ = open_jack_client(options_.client_name, options_.server, why);
  if (client_ == nullptr) return why;
  drive_port_ = jack_port_register(client_, "drive", JACK_DEFAULT_AUDIO_TYPE, JackPortIsInput, 0);
  acceleration_port_ =
      jack_port_register(client_, "acceleration", JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput, 0);
  position_port_ =
      jack_port_register(client_, "position", JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput, 0);
  if (drive_port_ == nullptr || acceleration_port_ == nullptr || position_port_ == nullptr) {
    stop();
    return "cannot register the plant's ports on " + server;
  }
  rate_hz_ = jack_get_sample_rate(client_);
  try {
    plant_ =
        std::make_unique<ShakerPlant>(model_, options_.positive_well, options_.shaker,
                                      options_.sensors, rate_hz_, options_.substeps, options_.seed);
  } catch (const InputError& error) {
    stop();
    return error.what();
  }
  shutdown_.clear();
  jack_set_process_callback(client_, plant_process_callback, this);
  jack_on_info_shutdown(client_, plant_shutdown_callback, this);
  if (jack_activate(client_) != 0) {
    stop();
    return "cannot activate the plant on " + server;
  }
  return "";
}

void JackPlant::stop() {
  if (client_ == nullptr) return;
  close_jack_client(client_, shutdown_);
  client_ = nullptr;
  drive_port_ = acceleration_port_ = position_port_ = nullptr;
}

}  // namespace oscilab::daq

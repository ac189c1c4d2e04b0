#pragma once
// The layout the stream tests send: the rig's two channels at 512 Hz (an accelerometer for the
// base, a vibrometer for the mass) with their ADC scales.
#include "daq/recording/sidecar.h"

namespace oscilab::daq::testing {

inline Sidecar two_channel_layout() {
  Sidecar s;
  s.sample_rate_hz = 512.0;
  s.mass_kg = 0.26;
  ChannelInfo acc;
  acc.name = "base_acc";
  acc.scale = 3e-5;
  ChannelInfo y;
  y.name = "y";
  y.role = ChannelRole::Mass;
  y.quantity = Quantity::Displacement;
  y.unit = "m";
  y.scale = 1e-7;
  s.channels = {acc, y};
  return s;
}

}  // namespace oscilab::daq::testing

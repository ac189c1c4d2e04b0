#pragma once

#include <string>

#include "daq/recording/recording.h"

namespace oscilab::daq {

/// What a recording holds, as text for a person (`oscilab-cli info`): path, container, rate,
/// samples, duration, mass, each channel (role, quantity, unit in the file, sensor, and the
/// min / max / rms of its SI samples) and the excitation. Several lines, each ending in '\n'.
std::string describe_recording(const Recording& recording);

}  // namespace oscilab::daq

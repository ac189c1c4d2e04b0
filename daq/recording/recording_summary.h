#pragma once

#include <string>

#include "daq/recording/format_reader.h"
#include "daq/recording/recording.h"

namespace oscilab::daq {

/// What a recording holds, as text for a person (`oscilab-cli info`): path, container, rate,
/// samples, duration, mass, each channel (role, quantity, unit in the file, sensor, and the
/// min / max / rms of its SI samples) and the excitation. Several lines, each ending in '\n'.
std::string describe_recording(const Recording& recording);

/// What a file holds before any sidecar maps it (`oscilab-cli info` of a file without one): its
/// container, its properties, and each signal with the name a sidecar's "source" uses, its
/// length, columns, stored type, unit and rate as the file states them, and its properties.
std::string describe_file_contents(const std::string& path, const FileContents& contents);

}  // namespace oscilab::daq

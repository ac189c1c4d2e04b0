#pragma once

// The format's own scaling of a TDMS channel: its NI_Scale[n] properties, a chain of linear
// scales from the stored values or from one DAQmx scaler's values.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "daq/recording/formats/tdms_segments.h"

namespace oscilab::daq::tdms {

/// The number property `name` of `properties`, or nothing when it is missing or not a number.
std::optional<double> number_property(const nlohmann::json& properties, const std::string& name);

// The format's own scaling of a channel (its NI_Scale[n] properties): the DAQmx scaler its
// values start from (none: the channel's only scaler, or its stored values), then each linear
// step in order.
struct ScalePlan {
  std::optional<std::uint32_t> scale_id;
  std::vector<std::pair<double, double>> steps;  // value → slope × value + intercept
};

/// The scaling of `object`, a channel of the file at `path` (named in messages); throws
/// InputError when its scales are not linear or do not chain.
ScalePlan scale_plan(const TdmsObject& object, const std::string& path);

}  // namespace oscilab::daq::tdms

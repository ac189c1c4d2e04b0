#include "daq/live/alarm_monitor.h"

#include <algorithm>
#include <cmath>

namespace oscilab::daq {
namespace {

constexpr double kRearmFraction = 0.9;  // re-armed below this share of the limit

const char* name_of(AlarmQuantity quantity) {
  switch (quantity) {
    case AlarmQuantity::RelativeDisplacement:
      return "|z|";
    case AlarmQuantity::BaseDisplacement:
      return "|b| (integration drift)";
    case AlarmQuantity::Force:
      return "|f|";
  }
  return "?";
}

}  // namespace

AlarmMonitor::AlarmMonitor(AlarmLimits limits, double sample_rate_hz)
    : limits_(limits),
      rearm_samples_(static_cast<std::uint64_t>(std::max(1.0, std::floor(sample_rate_hz)))) {}

const std::optional<double>& AlarmMonitor::limit(AlarmQuantity quantity) const {
  switch (quantity) {
    case AlarmQuantity::RelativeDisplacement:
      return limits_.max_abs_z_m;
    case AlarmQuantity::BaseDisplacement:
      return limits_.max_abs_base_m;
    case AlarmQuantity::Force:
      break;
  }
  return limits_.max_abs_force_n;
}

void AlarmMonitor::check(AlarmQuantity quantity, std::uint64_t sample, double value,
                         std::vector<Alarm>& raised) {
  const std::optional<double>& max_abs = limit(quantity);
  if (!max_abs || !std::isfinite(value)) return;
  const auto k = static_cast<std::size_t>(quantity);
  const double magnitude = std::abs(value);
  if (armed_[k] && magnitude > *max_abs) {
    armed_[k] = false;
    below_limit_samples_[k] = 0;
    raised.push_back({sample, std::string(name_of(quantity)) + " = " + std::to_string(magnitude) +
                                  " exceeds " + std::to_string(*max_abs)});
  } else if (!armed_[k]) {
    if (magnitude < kRearmFraction * *max_abs) {
      if (++below_limit_samples_[k] >= rearm_samples_) armed_[k] = true;
    } else {
      below_limit_samples_[k] = 0;
    }
  }
}

}  // namespace oscilab::daq

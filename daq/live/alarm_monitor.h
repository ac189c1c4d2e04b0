#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace oscilab::daq {

/// Limits whose crossing raises an alarm (logged and shown), in SI; unset: not checked.
struct AlarmLimits {
  std::optional<double> max_abs_z_m;      // relative displacement amplitude
  std::optional<double> max_abs_base_m;   // integrated table displacement: integration drift
  std::optional<double> max_abs_force_n;  // f = −m b̈
};

/// The quantities an alarm watches.
enum class AlarmQuantity { RelativeDisplacement, BaseDisplacement, Force };

/// Watches |z|, |b| and |f| against their limits. An alarm is raised when a value exceeds its
/// limit, and re-armed once the value has stayed below 90 % of the limit for a second of
/// samples: a quantity that swings through zero every cycle (f, b) raises one alarm per
/// excursion, not one per cycle.
///
/// Not thread-safe: the acquisition thread's. check() allocates only to report an alarm.
class AlarmMonitor {
 public:
  struct Alarm {
    std::uint64_t sample = 0;
    std::string text;  // e.g. "|z| = 0.012 exceeds 0.01"
  };

  AlarmMonitor() = default;
  AlarmMonitor(AlarmLimits limits, double sample_rate_hz);

  /// Checks `value` of `quantity` at `sample`; a raised alarm is appended to `raised`. A
  /// non-finite value (not known yet, or left out) neither raises nor re-arms.
  void check(AlarmQuantity quantity, std::uint64_t sample, double value,
             std::vector<Alarm>& raised);
  bool watches(AlarmQuantity quantity) const { return limit(quantity).has_value(); }

 private:
  const std::optional<double>& limit(AlarmQuantity quantity) const;

  AlarmLimits limits_;
  std::uint64_t rearm_samples_ = 1;  // a second of samples
  bool armed_[3] = {true, true, true};
  std::uint64_t below_limit_samples_[3] = {0, 0, 0};
};

}  // namespace oscilab::daq

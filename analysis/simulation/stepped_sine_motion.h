#pragma once

#include <vector>

#include "analysis/simulation/table_motion.h"

namespace oscilab::analysis {

/// The stepped-sine test of §3.2: a sine at fixed frequency whose force amplitude steps through
/// `levels_n`, each held for `hold_s`, with a C² ramp of `ramp_s` from the previous level at the
/// start of each hold (from rest for the first), after a quiet lead-in at rest.
///
///   timeline: [0, lead_in) rest │ level 0: [ramp │ steady] │ level 1: [ramp │ steady] │ ...
struct SteppedSineSchedule {
  double frequency_hz = 9.0;  // ν of §3.2
  std::vector<double> levels_n;
  double hold_s = 10.0;    // per level, ramp included
  double ramp_s = 0.5;     // amplitude ramp at the start of each hold
  double lead_in_s = 2.5;  // rest before the first level (lets the analysis see the sensor floor)

  double duration_s() const;
  /// Steady part of level i (after its ramp): [start, end).
  double steady_start_s(std::size_t level) const;
  double steady_end_s(std::size_t level) const;
  /// Forcing amplitude f0(t) with its time derivatives.
  SmoothStep amplitude_n(double t_s) const;
};

/// Table motion that produces the schedule's force on a mass m: b(t) = A(t) sin(ωt) with
/// A(t) = f0(t) / (m ω²), so that in every steady hold f = −m b̈ = f0 sin(ωt) exactly (eq. (11)).
/// During ramps b̈ also holds the terms of A' and A'' (b̈ = (A'' − ω²A) sin ωt + 2ωA' cos ωt).
class SteppedSineMotion final : public TableMotion {
 public:
  /// Throws InputError on a non-positive frequency, mass, hold, or ramp longer than the hold.
  SteppedSineMotion(SteppedSineSchedule schedule, double mass_kg);

  const SteppedSineSchedule& schedule() const { return schedule_; }
  TableState at(double t_s) const override;
  double duration_s() const override { return schedule_.duration_s(); }

 private:
  SteppedSineSchedule schedule_;
  double mass_kg_;
};

}  // namespace oscilab::analysis

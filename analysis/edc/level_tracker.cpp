#include "analysis/edc/level_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "analysis/common/quantile.h"

namespace oscilab::analysis {
namespace {

// 1.4826 · median absolute deviation: σ of Gaussian data, robust to outliers.
double robust_sigma(const std::vector<double>& values, double centre) {
  std::vector<double> deviations;
  deviations.reserve(values.size());
  for (double v : values) deviations.push_back(std::abs(v - centre));
  return 1.4826 * median(deviations);
}

// The steady part [first, last) of a level's per-cycle values: the transient decays into a band
// around the final value (median of the last third, ±4 robust σ + rel_tol·|value|). It starts at
// the first of three consecutive cycles inside the band; up to three trailing cycles outside it
// (a cycle cut by the next ramp) are dropped.
struct SteadyRange {
  std::size_t first = 0;
  std::size_t last = 0;
};

SteadyRange steady_range(const std::vector<double>& x, double rel_tol) {
  if (x.size() < 3) return {0, x.size()};
  const std::vector<double> tail(x.end() - static_cast<std::ptrdiff_t>(x.size() / 3), x.end());
  const double final_value = median(tail);
  const double band = 4.0 * robust_sigma(tail, final_value) + rel_tol * std::abs(final_value);
  const auto inside = [&](std::size_t i) { return std::abs(x[i] - final_value) <= band; };
  std::size_t last = x.size();
  while (last > 0 && x.size() - last < 3 && !inside(last - 1)) --last;
  std::size_t first = 0;
  while (first + 2 < last && !(inside(first) && inside(first + 1) && inside(first + 2))) ++first;
  if (first + 2 >= last) first = last;  // never settled
  return {first, last};
}

// Relative change of the first three harmonics between consecutive cycles.
double harmonic_change(const CycleFit& a, const CycleFit& b) {
  double diff = 0.0, norm = 0.0;
  const std::size_t n = std::min<std::size_t>({3, a.z_h.size(), b.z_h.size()});
  for (std::size_t h = 0; h < n; ++h) {
    diff += std::norm(a.z_h[h] - b.z_h[h]);
    norm += std::norm(b.z_h[h]);
  }
  return norm > 0 ? std::sqrt(diff / norm) : 0.0;
}

}  // namespace

std::string LevelResult::flags() const {
  std::string text;
  const auto add = [&](const char* flag) {
    if (!text.empty()) text += ';';
    text += flag;
  };
  if (!period1) add("not-period-1");
  if (cross_well) add("cross-well");
  if (few_cycles) add("few-cycles");
  if (base_constant) add("base-constant");
  if (mass_constant) add("mass-constant");
  if (negative_edc) add("negative-edc");
  if (non_finite) add("non-finite");
  if (short_window) add("short-window");
  if (beyond_record) add("beyond-record");
  return text;
}

std::vector<std::string> degenerate_level_notes(const std::vector<LevelResult>& levels) {
  struct Fault {
    bool LevelResult::*flag;
    const char* text;  // follows "N of M levels"
  };
  static const Fault kFaults[] = {
      {&LevelResult::base_constant,
       "base-constant: the base channel shows no motion above its noise, so no excitation is "
       "measured; check that channel's wiring, role and scale"},
      {&LevelResult::mass_constant,
       "mass-constant: the mass channel shows no motion above its noise, so the EDC is noise; "
       "check that channel's wiring, role and scale"},
      {&LevelResult::negative_edc,
       "negative-edc: the energy dissipated per cycle is negative beyond its noise, which a "
       "passive specimen cannot do; the base and mass roles (or a channel's sign) are likely "
       "swapped"},
      {&LevelResult::non_finite,
       "non-finite: the results overflow; a channel's values or its scale are absurd"},
      {&LevelResult::short_window,
       "short-window: the sidecar's steady window is shorter than one forcing period and holds "
       "no cycle"},
      {&LevelResult::beyond_record,
       "beyond-record: the sidecar's steady window reaches past the end of the record"},
  };
  std::vector<std::string> notes;
  for (const Fault& fault : kFaults) {
    const auto count = std::count_if(levels.begin(), levels.end(),
                                     [&](const LevelResult& l) { return l.*(fault.flag); });
    if (count == 0) continue;
    notes.push_back(std::to_string(count) + " of " + std::to_string(levels.size()) +
                    " levels flagged " + fault.text);
  }
  return notes;
}

namespace {

// The level's steady cycles: trailing cycles that already belong to the ramp to the next level
// dropped, then the steady range of the EDC (eq. (13)); the transient and steady counts into
// `level`.
std::vector<CycleFit> steady_cycles(const std::vector<CycleFit>& cycles,
                                    const LevelOptions& options, LevelResult& level) {
  // Cycles at the end of a detected level may already belong to the ramp to the next one: drop
  // trailing cycles whose force amplitude is off the level's by more than 0.1 % or 5 σ (a
  // ramp's first cycle moves f0 by a few tenths of a percent and its EDC by far more).
  std::vector<double> f0_all;
  for (const CycleFit& c : cycles) f0_all.push_back(c.f0_n);
  const double f0_level = median(f0_all);
  const double f0_band = std::max(1e-3 * f0_level, 5.0 * robust_sigma(f0_all, f0_level));
  std::size_t end = cycles.size();
  while (end > 0 && std::abs(cycles[end - 1].f0_n - f0_level) > f0_band) --end;
  const std::vector<CycleFit> all(cycles.begin(),
                                  cycles.begin() + static_cast<std::ptrdiff_t>(end));
  if (all.empty()) return {};
  std::vector<double> edc;
  edc.reserve(all.size());
  for (const CycleFit& c : all) edc.push_back(c.edc_j);
  const SteadyRange range = steady_range(edc, options.steady_rel_tol);
  const std::vector<CycleFit> steady(all.begin() + static_cast<std::ptrdiff_t>(range.first),
                                     all.begin() + static_cast<std::ptrdiff_t>(range.last));
  level.transient_cycles = static_cast<int>(range.first);
  level.cycles = static_cast<int>(steady.size());
  level.few_cycles = level.cycles < options.min_steady_cycles;
  return steady;
}

// What the cycles scatter with: each cycle's residuals, samples and harmonic change from the one
// before.
struct CycleScatter {
  std::vector<double> mass_residuals, base_residuals, samples, changes;
};

// The means over the steady cycles (EDC and its standard deviation, f0, |Z1|, lag, z range)
// into `level`.
CycleScatter average_cycles(const std::vector<CycleFit>& steady, const LevelOptions& options,
                            LevelResult& level) {
  const double n = static_cast<double>(steady.size());
  double sum = 0, sum2 = 0, eq13 = 0, trapz = 0, f0 = 0, z1 = 0, lag = 0, z_mean = 0;
  level.z_min_m = steady.front().z_min_m;
  level.z_max_m = steady.front().z_max_m;
  CycleScatter scatter;
  for (std::size_t i = 0; i < steady.size(); ++i) {
    const CycleFit& c = steady[i];
    sum += c.edc_j;
    sum2 += c.edc_j * c.edc_j;
    eq13 += c.edc_eq13_j;
    trapz += c.edc_trapz_j;
    f0 += c.f0_n;
    z1 += std::abs(c.z_h.front());
    lag += c.lag_rad;
    z_mean += c.z_mean_m;
    level.z_min_m = std::min(level.z_min_m, c.z_min_m);
    level.z_max_m = std::max(level.z_max_m, c.z_max_m);
    // Only a displacement channel knows where z is; a velocity's z has no mean.
    level.cross_well = level.cross_well ||
                       (options.mass_quantity == MotionQuantity::Displacement &&
                        c.z_min_m < options.well_boundary_m && c.z_max_m > options.well_boundary_m);
    scatter.mass_residuals.push_back(c.mass_residual_rms);
    scatter.base_residuals.push_back(c.base_residual_rms);
    scatter.samples.push_back(c.samples);
    if (i > 0) scatter.changes.push_back(harmonic_change(steady[i - 1], c));
  }
  level.edc_mean_j = sum / n;
  level.edc_std_j = n > 1 ? std::sqrt(std::max(0.0, (sum2 - sum * sum / n) / (n - 1))) : 0.0;
  level.edc_eq13_mean_j = eq13 / n;
  level.edc_trapz_mean_j = trapz / n;
  level.f0_n = f0 / n;
  level.z1_abs_m = z1 / n;
  level.lag_rad = lag / n;
  level.z_mean_m = z_mean / n;
  level.start_s = steady.front().start_s;
  level.end_s = steady.back().end_s;

  return scatter;
}

// The level's noise floor, period-1 test, degenerate-data flags and well, from its steady cycles'
// means (already in `level`) and scatter.
void judge_level(const std::vector<CycleFit>& steady, const CycleScatter& scatter,
                 const LevelOptions& options, LevelResult& level) {
  const double n = static_cast<double>(steady.size());
  // Noise floor of the mean EDC from the sensor noise (the fits' residual rms; at high levels
  // this also holds harmonics above H, so the floor errs on the high side there). Over a cycle of
  // N samples a least-squares sine/cosine coefficient of white noise σ has σ·√(2/N). Eq. (13),
  // S = π f0 |Z1| sin θ1, then moves by π f0 σ_z through the quadrature part of Z1 (σ_z the
  // displacement noise of y − b) and by S σ_F / f0 through the force amplitude (σ_F the noise
  // of F1 = m·B̈1). The mean of n independent cycles divides by √n.
  const double omega = 2.0 * std::numbers::pi * options.freq_hz;
  const double n_per_cycle = median(scatter.samples);
  const double coefficient_noise = std::sqrt(2.0 / n_per_cycle);
  const double mass_noise =
      median(scatter.mass_residuals) / std::pow(omega, derivative_order(options.mass_quantity));
  const double base_noise_disp =
      median(scatter.base_residuals) / std::pow(omega, derivative_order(options.base_quantity));
  const double sigma_z = std::hypot(mass_noise, base_noise_disp) * coefficient_noise;
  const double sigma_f = options.mass_kg * base_noise_disp * omega * omega * coefficient_noise;
  const double sigma_cycle =
      std::hypot(std::numbers::pi * level.f0_n * sigma_z,
                 level.f0_n > 0 ? level.edc_mean_j * sigma_f / level.f0_n : 0.0);
  level.edc_noise_floor_j = sigma_cycle / std::sqrt(n);

  // Period 1: the harmonics repeat from cycle to cycle within their noise (the relative change
  // of three harmonics has noise ≈ √(2·6/N)·σ_z/|Z|; demand 3× that plus 2 %), and the
  // per-cycle EDC scatters no more than 10× its predicted noise (plus 0.5 %). A period-2 or
  // chaotic response fails one or both (Fig. 17).
  if (!scatter.changes.empty()) {
    level.period1_change = median(scatter.changes);
    const double noise_change = std::sqrt(12.0 / n_per_cycle) *
                                std::hypot(mass_noise, base_noise_disp) /
                                std::max(level.z1_abs_m, 1e-300);
    const bool harmonics_repeat = level.period1_change <= 3.0 * noise_change + 0.02;
    const bool energy_repeats =
        level.edc_std_j <= 10.0 * sigma_cycle + 5e-3 * std::abs(level.edc_mean_j);
    level.period1 = harmonics_repeat && energy_repeats;
  }

  // Degenerate data. Over a cycle of N samples a least-squares sine/cosine coefficient of white
  // noise σ has σ·√(2/N), so the first harmonic of a channel that holds no tone is Rayleigh
  // distributed with mean 1.25 of that and exceeds 5 of it with probability e^(−12.5) ≈ 4e-6.
  // A channel whose first harmonic stays within 5 such σ does not measure the motion at all (a
  // constant or disconnected channel: both are 0 then). Its phase, and the EDC, are noise.
  constexpr double kToneSigmas = 5.0;
  double y1 = 0.0;
  for (const CycleFit& c : steady) y1 += c.y1_abs_m;
  y1 /= n;
  level.base_constant = !(level.f0_n > kToneSigmas * sigma_f);
  level.mass_constant = !(y1 > kToneSigmas * mass_noise * coefficient_noise);
  // A passive specimen dissipates: EDC ≥ 0. A mean below zero by more than 5 of its standard
  // errors (the larger of the predicted floor and the observed scatter over √n) is not noise
  // (p < 3e-7) but swapped base and mass roles or a channel of the wrong sign.
  const double edc_standard_error =
      std::max(level.edc_noise_floor_j, level.edc_std_j / std::sqrt(n));
  level.negative_edc = level.edc_mean_j < -kToneSigmas * edc_standard_error;
  level.non_finite = !(std::isfinite(level.edc_mean_j) && std::isfinite(level.edc_std_j) &&
                       std::isfinite(level.edc_noise_floor_j) && std::isfinite(level.f0_n) &&
                       std::isfinite(level.z1_abs_m));

  if (level.cross_well) {
    level.well = Well::CrossWell;
  } else if (std::isfinite(level.z_mean_m) &&
             options.mass_quantity == MotionQuantity::Displacement) {
    level.well = level.z_mean_m > options.well_boundary_m ? Well::Positive : Well::Negative;
  } else if (options.well_hint_positive) {
    level.well = well_of(*options.well_hint_positive);
  } else {
    level.well = Well::Unknown;
  }
}

}  // namespace

LevelResult summarise_level(const std::vector<CycleFit>& cycles, const LevelOptions& options) {
  LevelResult level;
  if (cycles.empty()) return level;
  const std::vector<CycleFit> steady = steady_cycles(cycles, options, level);
  if (steady.empty()) return level;
  const CycleScatter scatter = average_cycles(steady, options, level);
  judge_level(steady, scatter, options, level);
  return level;
}

LevelTracker::LevelTracker(LevelOptions options) : options_(std::move(options)) {}

int LevelTracker::window_of(const CycleFit& cycle) const {
  for (std::size_t w = 0; w < options_.windows.size(); ++w) {
    const LevelWindow& window = options_.windows[w];
    // A little tolerance: a cycle may end a rounding error past the window's end.
    if (cycle.start_s >= window.start_s - 1e-9 && cycle.end_s <= window.end_s + 1e-6) {
      return static_cast<int>(w);
    }
  }
  return -1;
}

bool LevelTracker::starts_new_level(const CycleFit& cycle) const {
  if (level_cycles_.empty()) return false;
  std::vector<double> f0;
  for (const CycleFit& c : level_cycles_) f0.push_back(c.f0_n);
  const double reference = median(f0);
  const double sigma = f0.size() > 4 ? robust_sigma(f0, reference) : 0.0;
  return std::abs(cycle.f0_n - reference) >
         std::max(options_.level_change_rel * reference, 5.0 * sigma);
}

namespace {

// What a sidecar window says of its level, whatever its cycles: too short to hold one, or
// reaching past the end of the stream (a tolerance of 1 µs, as window_of's).
void mark_window(LevelResult& level, const LevelWindow& window, const LevelOptions& options,
                 double stream_end_s) {
  level.short_window = options.freq_hz > 0 && window.end_s - window.start_s < 1.0 / options.freq_hz;
  level.beyond_record = std::isfinite(window.end_s) && window.end_s > stream_end_s + 1e-6;
}

}  // namespace

void LevelTracker::close_level(std::vector<LevelResult>& finished, double stream_end_s) {
  ++levels_closed_;
  // A sidecar level is always reported (flagged when it is short); a detected one needs enough
  // steady cycles to be a level at all, not a ramp between two.
  const bool from_window = level_window_ >= 0;
  if (from_window || static_cast<int>(level_cycles_.size()) >= options_.min_steady_cycles) {
    LevelResult level = summarise_level(level_cycles_, options_);
    if (from_window) {
      report_windows_without_cycles(static_cast<std::size_t>(level_window_), finished,
                                    stream_end_s);
      mark_window(level, options_.windows[static_cast<std::size_t>(level_window_)], options_,
                  stream_end_s);
      next_window_ = std::max(next_window_, static_cast<std::size_t>(level_window_) + 1);
    }
    if (from_window || !level.few_cycles) finished.push_back(level);
  }
  level_cycles_.clear();
  level_window_ = -1;
}

void LevelTracker::report_windows_without_cycles(std::size_t until,
                                                 std::vector<LevelResult>& finished,
                                                 double stream_end_s) {
  for (; next_window_ < std::min(until, options_.windows.size()); ++next_window_) {
    const LevelWindow& window = options_.windows[next_window_];
    // No cycle to measure: the level is known by its window alone.
    LevelResult level;
    level.start_s = window.start_s;
    level.end_s = std::isfinite(window.end_s) ? window.end_s : window.start_s;
    level.few_cycles = true;
    mark_window(level, window, options_, stream_end_s);
    finished.push_back(level);
  }
}

void LevelTracker::push(const std::vector<CycleFit>& cycles, std::vector<LevelResult>& finished) {
  for (const CycleFit& cycle : cycles) {
    if (options_.windowed || !options_.windows.empty()) {
      const int window = window_of(cycle);
      if (window != level_window_ && !level_cycles_.empty()) {
        close_level(finished, std::numeric_limits<double>::infinity());
      }
      if (window < 0) continue;  // ramps and gaps between the sidecar's levels
      level_window_ = window;
      level_cycles_.push_back(cycle);
    } else {
      if (starts_new_level(cycle)) close_level(finished, std::numeric_limits<double>::infinity());
      level_cycles_.push_back(cycle);
    }
  }
}

void LevelTracker::finish(std::vector<LevelResult>& finished, double stream_end_s) {
  if (!level_cycles_.empty()) close_level(finished, stream_end_s);
  report_windows_without_cycles(options_.windows.size(), finished, stream_end_s);
}

void LevelTracker::add_window(const LevelWindow& window) {
  options_.windowed = true;
  options_.windows.push_back(window);
}

void LevelTracker::end_window(double end_s) {
  if (!options_.windows.empty() && end_s < options_.windows.back().end_s) {
    options_.windows.back().end_s = std::max(end_s, options_.windows.back().start_s);
  }
}

std::optional<LevelResult> LevelTracker::current() const {
  if (level_cycles_.empty()) return std::nullopt;
  const std::size_t n = level_cycles_.size();
  const bool stale = !current_summary_ || summary_level_ != levels_closed_ || n < summary_cycles_ ||
                     n >= summary_cycles_ + std::max<std::size_t>(1, summary_cycles_ / 64);
  if (stale) {
    current_summary_ = summarise_level(level_cycles_, options_);
    summary_cycles_ = n;
    summary_level_ = levels_closed_;
  }
  return current_summary_;
}

}  // namespace oscilab::analysis

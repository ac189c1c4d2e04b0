#include "analysis/pipeline/derived_signals.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
enum Filter { kB, kBDot, kYDot, kYDDot, kY };

}  // namespace

DerivedSignals::DerivedSignals(const Options& options) : options_(options) {
  if (!(options.sample_rate_hz > 0) || !(options.mass_kg > 0) || options.max_rows < 1) {
    throw InputError("derived signals: sample rate, mass and block size must be positive");
  }
  const int d_base = derivative_order(options.base_quantity);
  const int d_mass = derivative_order(options.mass_quantity);
  const auto filter = [&](int order) -> std::unique_ptr<StreamingIntegrator> {
    if (order == 0) return nullptr;  // the delayed sample itself
    StreamingIntegrator::Options o;
    o.sample_rate_hz = options.sample_rate_hz;
    o.order = order;
    o.highpass_hz = order < 0 ? options.integration_highpass_hz : 0.0;
    o.lowpass_hz = std::min(options.derivative_lowpass_hz, 0.45 * options.sample_rate_hz);
    o.latency_s = options.latency_s;
    return std::make_unique<StreamingIntegrator>(o);
  };
  filters_[kB] = filter(-d_base);
  filters_[kBDot] = filter(1 - d_base);
  filters_[kYDot] = filter(1 - d_mass);
  filters_[kYDDot] = filter(2 - d_mass);
  filters_[kY] = filter(-d_mass);
  // Every filter has the same latency; the channels' own samples are read that far back.
  for (const auto& f : filters_) {
    if (f) latency_ = f->latency_samples();
  }
  delayed_base_.assign(static_cast<std::size_t>(latency_) + 1, 0.0);
  delayed_mass_.assign(static_cast<std::size_t>(latency_) + 1, 0.0);
}

DerivedSignals::~DerivedSignals() = default;

DerivedSignals::Block DerivedSignals::make_block() const {
  Block block;
  const auto n = static_cast<std::size_t>(options_.max_rows);
  for (auto* v : {&block.b_m, &block.z_m, &block.z_dot_m_s, &block.restoring_force_n}) {
    v->assign(n, kNaN);
  }
  return block;
}

void DerivedSignals::exclude(std::uint64_t from, std::uint64_t to) {
  last_fault_ = fault_seen_ ? std::max(last_fault_, std::max(from, to)) : std::max(from, to);
  fault_seen_ = true;
}

void DerivedSignals::push(std::uint64_t first_sample, const double* base_si, const double* mass_si,
                          int rows, Block& out) {
  out.count = 0;
  if (out.b_m.size() < static_cast<std::size_t>(rows)) {
    throw InputError("derived signals: a block of " + std::to_string(rows) +
                     " rows is larger than the " + std::to_string(options_.max_rows) +
                     " announced");
  }
  const auto latency = static_cast<std::uint64_t>(latency_);
  const std::size_t ring = delayed_base_.size();
  for (int r = 0; r < rows; ++r) {
    const std::uint64_t sample = first_sample + static_cast<std::uint64_t>(r);
    double filtered[5];
    for (int k = 0; k < 5; ++k) {
      filtered[k] = filters_[k] ? filters_[k]->push(k <= kBDot ? base_si[r] : mass_si[r]) : kNaN;
    }
    delayed_base_[sample % ring] = base_si[r];
    delayed_mass_[sample % ring] = mass_si[r];
    if (sample < latency) continue;
    const std::uint64_t at = sample - latency;
    const double base_at = delayed_base_[at % ring], mass_at = delayed_mass_[at % ring];
    // A filter spans ±latency: near a fault (or before it is full) its output is left out.
    const bool ready = std::all_of(std::begin(filters_), std::end(filters_),
                                   [](const auto& f) { return !f || f->ready(); });
    const bool trusted = ready && (!fault_seen_ || sample > last_fault_ + 2 * latency);
    const auto pick = [&](int k, double delayed) {
      if (!trusted) return kNaN;
      return filters_[k] ? filtered[k] : delayed;
    };
    const double b = pick(kB, base_at), b_dot = pick(kBDot, base_at);
    const double y = pick(kY, mass_at), y_dot = pick(kYDot, mass_at);
    const double y_ddot = pick(kYDDot, mass_at);
    if (out.count == 0) out.first_sample = at;
    const auto i = static_cast<std::size_t>(out.count++);
    out.b_m[i] = b;
    if (options_.mass_is_relative) {  // the mass channel measures z itself: R = f − m z̈
      const double f = options_.base_quantity == MotionQuantity::Acceleration
                           ? excitation_force_n(options_.mass_kg, base_at)
                           : kNaN;
      out.z_m[i] = y;
      out.z_dot_m_s[i] = y_dot;
      out.restoring_force_n[i] = f - options_.mass_kg * y_ddot;
    } else {  // z = y − b, ż = ẏ − ḃ, R = f − m z̈ = −m ÿ (eq. (1))
      out.z_m[i] = y - b;
      out.z_dot_m_s[i] = y_dot - b_dot;
      out.restoring_force_n[i] = -options_.mass_kg * y_ddot;
    }
  }
}

}  // namespace oscilab::analysis

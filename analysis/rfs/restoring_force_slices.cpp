#include "analysis/rfs/restoring_force_slices.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "analysis/common/input_error.h"
#include "analysis/common/quantile.h"
#include "analysis/rfs/polynomial_fit.h"

namespace oscilab::analysis {
namespace {

// Mean force per bin of x over [lo, hi), filled as samples come; empty bins are left out.
class SliceBins {
 public:
  SliceBins(double lo, double hi, int bins)
      : lo_(lo), width_((hi - lo) / bins), bins_(static_cast<std::size_t>(bins)) {
    for (int b = 0; b < bins; ++b) bins_[static_cast<std::size_t>(b)].x = lo + (b + 0.5) * width_;
  }
  void add(double x, double force_n) {
    const int b = static_cast<int>(std::floor((x - lo_) / width_));
    if (b < 0 || b >= static_cast<int>(bins_.size())) return;
    bins_[static_cast<std::size_t>(b)].force_n += force_n;
    ++bins_[static_cast<std::size_t>(b)].samples;
  }
  std::vector<SliceBin> filled() const {
    std::vector<SliceBin> out;
    for (SliceBin bin : bins_) {
      if (bin.samples == 0) continue;
      bin.force_n /= bin.samples;
      out.push_back(bin);
    }
    return out;
  }

 private:
  double lo_, width_;
  std::vector<SliceBin> bins_;
};

// The 1 % and 99 % quantiles of values that come one at a time, among at most `max_count`.
class CentralRange {
 public:
  explicit CentralRange(std::size_t max_count) : low_(0.01, max_count), high_(0.99, max_count) {}
  void add(double value) {
    low_.add(value);
    high_.add(value);
  }
  std::size_t count() const { return low_.count(); }
  double low() const { return low_.value(); }
  double high() const { return high_.value(); }

 private:
  StreamedQuantile low_, high_;
};

// A pass over records in memory, each one span.
MotionPass memory_pass(const std::vector<const MotionSignals*>& records) {
  return [&records](const MotionSpanVisit& visit) {
    for (const MotionSignals* s : records) {
      if (s->t_s.size() > 0) visit(*s, s->t_s[s->t_s.size() - 1]);
    }
  };
}

Eigen::Index total_samples(const std::vector<const MotionSignals*>& records) {
  Eigen::Index total = 0;
  for (const MotionSignals* s : records) total += s->t_s.size();
  return total;
}

}  // namespace

// The slices are made in passes over the records' motion, so that none is held whole (a
// streamed record is transformed again for each); what each pass needs comes from the one
// before:
//   1. the 99th percentile of |ż|, which sets the band ε_s;
//   2. in the band: the 1–99 % range of z (the bins, the z range) and the fit's centring;
//   3. in the band: the bins and the fit's normal equations;
//   4. in the band: the fit's residual, for its standard errors.
// The damping slices then take two more: the 1–99 % range of ż near each centre, and the bins.
StiffnessSlice stiffness_slice(const MotionPass& pass, Eigen::Index max_samples,
                               const PipelineSettings& settings, int degree) {
  const double trim_s = settings.edge_trim_s;
  const auto bound = static_cast<std::size_t>(std::max<Eigen::Index>(0, max_samples));
  StreamedQuantile speed_p99(0.99, bound);
  pass([&](const MotionSignals& s, double end_s) {
    for_each_slice_sample(s, end_s, trim_s,
                          [&](Eigen::Index i) { speed_p99.add(std::abs(s.z_dot_m_s[i])); });
  });
  if (speed_p99.count() > bound) {
    throw std::logic_error("stiffness slice: a pass gave more samples than its bound");
  }
  StiffnessSlice slice;
  slice.velocity_band_m_s = settings.stiffness_velocity_band_rel * speed_p99.value();
  // Calls visit(z, R) for every sample in the band.
  const auto in_band = [&](const auto& visit) {
    pass([&](const MotionSignals& s, double end_s) {
      for_each_slice_sample(s, end_s, trim_s, [&](Eigen::Index i) {
        if (std::abs(s.z_dot_m_s[i]) < slice.velocity_band_m_s) {
          visit(s.z_m[i], s.restoring_force_n[i]);
        }
      });
    });
  };
  CentralRange z_range(bound);
  PolynomialFitter fitter(degree);
  in_band([&](double z, double) {
    z_range.add(z);
    fitter.add_to_range(z);
  });
  if (static_cast<int>(z_range.count()) < 10 * (degree + 1)) {
    throw InputError("restoring force: only " + std::to_string(z_range.count()) +
                     " samples with |z_dot| < " + std::to_string(slice.velocity_band_m_s) +
                     " m/s: too few for the stiffness slice");
  }
  slice.z_min_m = z_range.low();
  slice.z_max_m = z_range.high();
  SliceBins bins(slice.z_min_m, slice.z_max_m, settings.stiffness_bins);
  in_band([&](double z, double r) {
    bins.add(z, r);
    fitter.add_to_normal_equations(z, r);
  });
  slice.bins = bins.filled();
  fitter.solve();
  in_band([&](double z, double r) { fitter.add_to_residual(z, r); });
  slice.fit = fitter.result();
  return slice;
}

std::vector<DampingSlice> damping_slices(const MotionPass& pass, Eigen::Index max_samples,
                                         const StiffnessSlice& stiffness,
                                         const std::vector<double>& z_centers_m,
                                         const PipelineSettings& settings) {
  const double band_m =
      settings.damping_position_band_rel * (stiffness.z_max_m - stiffness.z_min_m);
  // Calls visit(c, ż, D) for every sample within the band of centre c.
  const auto near_centres = [&](const auto& visit) {
    pass([&](const MotionSignals& s, double end_s) {
      for_each_slice_sample(s, end_s, settings.edge_trim_s, [&](Eigen::Index i) {
        for (std::size_t c = 0; c < z_centers_m.size(); ++c) {
          if (std::abs(s.z_m[i] - z_centers_m[c]) < band_m) {
            visit(c, s.z_dot_m_s[i], s.restoring_force_n[i] - stiffness.fit.value(s.z_m[i]));
          }
        }
      });
    });
  };
  const auto bound = static_cast<std::size_t>(std::max<Eigen::Index>(0, max_samples));
  std::vector<CentralRange> ranges(z_centers_m.size(), CentralRange(bound));
  if (!z_centers_m.empty()) {
    near_centres([&](std::size_t c, double v, double) { ranges[c].add(v); });
  }
  std::vector<DampingSlice> slices(z_centers_m.size());
  std::vector<SliceBins> bins;
  for (std::size_t c = 0; c < z_centers_m.size(); ++c) {
    slices[c].z_center_m = z_centers_m[c];
    slices[c].position_band_m = band_m;
    const double extent = std::max(std::abs(ranges[c].low()), std::abs(ranges[c].high()));
    bins.emplace_back(-extent, extent, settings.damping_bins);
  }
  if (!z_centers_m.empty()) {
    near_centres([&](std::size_t c, double v, double d) { bins[c].add(v, d); });
  }
  for (std::size_t c = 0; c < z_centers_m.size(); ++c) {
    if (ranges[c].count() >= 10) slices[c].bins = bins[c].filled();
  }
  return slices;
}

StiffnessSlice stiffness_slice(const std::vector<const MotionSignals*>& records,
                               const PipelineSettings& settings, int degree) {
  return stiffness_slice(memory_pass(records), total_samples(records), settings, degree);
}

DampingSlice damping_slice(const std::vector<const MotionSignals*>& records,
                           const StiffnessSlice& stiffness, double z_center_m,
                           const PipelineSettings& settings) {
  return damping_slices(memory_pass(records), total_samples(records), stiffness, {z_center_m},
                        settings)
      .front();
}

}  // namespace oscilab::analysis

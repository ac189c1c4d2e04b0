#include "analysis/rfs/motion_spans.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/signal/gap_fill.h"

namespace oscilab::analysis {
namespace {

// The samples [offset, offset + count) of `whole`.
MotionSignals sub_span(const MotionSignals& whole, Eigen::Index offset, Eigen::Index count) {
  MotionSignals span;
  span.t_s = whole.t_s.segment(offset, count);
  span.z_m = whole.z_m.segment(offset, count);
  span.z_dot_m_s = whole.z_dot_m_s.segment(offset, count);
  span.restoring_force_n = whole.restoring_force_n.segment(offset, count);
  span.z_absolute = whole.z_absolute;
  return span;
}

// R near the record's invalid intervals is left out: the zero-phase filters spread a bad stretch
// over about one period of the integration high-pass on either side.
void leave_out_near_excluded(MotionSignals& s, const MeasurementChannels& channels,
                             const PipelineSettings& settings) {
  const double margin_s = 1.0 / settings.integration_highpass_hz;
  for (const TimeInterval& interval : channels.excluded) {
    for (Eigen::Index i = 0; i < s.t_s.size(); ++i) {
      if (interval.overlaps(s.t_s[i] - margin_s, s.t_s[i] + margin_s)) {
        s.restoring_force_n[i] = std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
}

// The motion of the samples `window` holds (with the record's metadata), its non-finite samples
// filled first.
MotionSignals filled_motion(MeasurementChannels& window, const PipelineSettings& settings) {
  fill_non_finite(window.base);
  fill_non_finite(window.mass);
  return motion_signals(window, settings, window.mass_kg.value_or(1.0));
}

Eigen::Index margin_samples(double sample_rate_hz, const PipelineSettings& settings,
                            const MotionSpanning& spanning) {
  return static_cast<Eigen::Index>(std::ceil(spanning.margin_highpass_periods /
                                             settings.integration_highpass_hz * sample_rate_hz));
}

}  // namespace

void for_each_motion_span(const MeasurementChannels& channels, const PipelineSettings& settings,
                          const MotionSpanVisit& visit, const CancelToken& cancel,
                          const MotionSpanning& spanning) {
  const double rate_hz = channels.sample_rate_hz;
  const Eigen::Index n = channels.sample_count();
  if (n == 0) return;
  const double record_end_s = static_cast<double>(n - 1) / rate_hz;
  // The record's metadata without its samples, to hold a window of them.
  MeasurementChannels window;
  window.name = channels.name;
  window.sample_rate_hz = rate_hz;
  window.mass_kg = channels.mass_kg;
  window.base_quantity = channels.base_quantity;
  window.mass_quantity = channels.mass_quantity;
  window.mass_is_relative = channels.mass_is_relative;

  const auto finite = [](const Eigen::VectorXd& x) { return x.array().isFinite().all(); };
  if (n <= spanning.whole_record_samples) {
    MotionSignals motion;
    if (!channels.source && finite(channels.base) && finite(channels.mass)) {
      motion = motion_signals(channels, settings, channels.mass_kg.value_or(1.0));  // no copy
    } else {
      window.base.resize(n);
      window.mass.resize(n);
      read_samples(*channels.open(), window.base.data(), window.mass.data(), n, channels.name);
      motion = filled_motion(window, settings);
    }
    leave_out_near_excluded(motion, channels, settings);
    visit(motion, record_end_s);
    return;
  }

  if (!(spanning.span_samples > 0) || !(spanning.margin_highpass_periods >= 0.0)) {
    throw InputError("motion spans: the span and its margin must be positive");
  }
  const Eigen::Index margin = margin_samples(rate_hz, settings, spanning);
  // The samples [held_first, held_first + held) of the record, read forward as spans need them.
  std::unique_ptr<ChannelReader> reader = channels.open();
  std::vector<double> base, mass;
  Eigen::Index held_first = 0, read_until = 0;
  for (Eigen::Index first = 0; first < n; first += spanning.span_samples) {
    if (cancel.cancelled()) return;
    const Eigen::Index end = std::min(n, first + spanning.span_samples);
    const Eigen::Index window_first = std::max<Eigen::Index>(0, first - margin);
    const Eigen::Index window_end = std::min(n, end + margin);
    // Drop what lies before the window, read up to its end.
    const auto dropped = static_cast<std::size_t>(window_first - held_first);
    base.erase(base.begin(), base.begin() + static_cast<std::ptrdiff_t>(dropped));
    mass.erase(mass.begin(), mass.begin() + static_cast<std::ptrdiff_t>(dropped));
    held_first = window_first;
    const auto wanted = static_cast<std::size_t>(window_end - held_first);
    const std::size_t held = base.size();
    base.resize(wanted);
    mass.resize(wanted);
    read_samples(*reader, base.data() + held, mass.data() + held, window_end - read_until,
                 channels.name);
    read_until = window_end;

    const auto length = static_cast<Eigen::Index>(wanted);
    window.base = Eigen::Map<const Eigen::VectorXd>(base.data(), length);
    window.mass = Eigen::Map<const Eigen::VectorXd>(mass.data(), length);
    const MotionSignals motion = filled_motion(window, settings);
    MotionSignals span = sub_span(motion, first - window_first, end - first);
    for (Eigen::Index i = 0; i < span.t_s.size(); ++i) {
      span.t_s[i] = static_cast<double>(first + i) / rate_hz;
    }
    leave_out_near_excluded(span, channels, settings);
    visit(span, record_end_s);
  }
}

SampleRange motion_window_range(Eigen::Index first, Eigen::Index end, Eigen::Index record_samples,
                                double sample_rate_hz, const PipelineSettings& settings,
                                const MotionSpanning& spanning) {
  const Eigen::Index margin = margin_samples(sample_rate_hz, settings, spanning);
  return {std::clamp<Eigen::Index>(first - margin, 0, record_samples),
          std::clamp<Eigen::Index>(end + margin, 0, record_samples)};
}

WindowMotion window_motion(const MeasurementChannels& window, Eigen::Index window_first,
                           Eigen::Index first, Eigen::Index end, const PipelineSettings& settings) {
  const Eigen::Index held = window.base.size();
  if (first < window_first || end > window_first + held || end < first ||
      window.mass.size() != held) {
    throw InputError(window.name + ": samples " + std::to_string(first) + " to " +
                     std::to_string(end) + " are not in the window read");
  }
  WindowMotion out;
  if (end == first) return out;
  MeasurementChannels filled = window;
  filled.source.reset();
  const MotionSignals motion = filled_motion(filled, settings);  // fills `filled`
  out.motion = sub_span(motion, first - window_first, end - first);
  for (Eigen::Index i = 0; i < out.motion.t_s.size(); ++i) {
    out.motion.t_s[i] = static_cast<double>(first + i) / window.sample_rate_hz;
  }
  leave_out_near_excluded(out.motion, window, settings);
  out.force_n = excitation_force(filled, settings).segment(first - window_first, end - first);
  return out;
}

}  // namespace oscilab::analysis

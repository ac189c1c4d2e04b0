#include "analysis/pipeline/measurement_pipeline.h"

#include <algorithm>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

CycleAnalyzer::Options analyzer_options(const PipelineSettings& settings, const StreamSetup& s) {
  CycleAnalyzer::Options options;
  options.fit.freq_hz = s.excitation_freq_hz;
  options.fit.mass_kg = s.mass_kg;
  options.fit.harmonics = settings.harmonics;
  options.fit.t_ref_s = 0.0;
  options.fit.base_quantity = s.base_quantity;
  options.fit.mass_quantity = s.mass_quantity;
  options.fit.mass_is_relative = s.mass_is_relative;
  options.sample_rate_hz = s.sample_rate_hz;
  options.t0_s = s.t0_s;
  return options;
}

LevelOptions level_options(const PipelineSettings& settings, const StreamSetup& s) {
  LevelOptions options;
  options.windows = s.level_windows;
  options.windowed = s.windowed_levels;
  options.freq_hz = s.excitation_freq_hz;
  options.mass_kg = s.mass_kg;
  options.base_quantity = s.base_quantity;
  options.mass_quantity = s.mass_quantity;
  options.well_boundary_m = settings.well_boundary_m;
  options.well_hint_positive = s.well_hint_positive;
  options.min_steady_cycles = settings.min_steady_cycles;
  options.level_change_rel = settings.level_change_rel;
  options.steady_rel_tol = settings.steady_rel_tol;
  return options;
}

const PipelineSettings& checked(const PipelineSettings& settings) {
  settings.validate();
  return settings;
}

}  // namespace

MeasurementPipeline::MeasurementPipeline(const PipelineSettings& settings, const StreamSetup& setup,
                                         bool keep_cycles)
    : setup_(setup),
      analyzer_(analyzer_options(checked(settings), setup)),
      tracker_(level_options(settings, setup)),
      keep_cycles_(keep_cycles) {}

void MeasurementPipeline::push(const SampleBlock& block) {
  const Eigen::Index n = block.samples.rows();
  if (n == 0) return;
  if (block.samples.cols() < 2) throw InputError("pipeline: a block needs base and mass columns");
  t_scratch_.resize(static_cast<std::size_t>(n));
  const double dt = 1.0 / setup_.sample_rate_hz;
  for (Eigen::Index i = 0; i < n; ++i) {
    t_scratch_[static_cast<std::size_t>(i)] = block.t0_s + static_cast<double>(i) * dt;
  }
  stream_end_s_ = std::max(stream_end_s_, block.t0_s + static_cast<double>(n) * dt);
  analyse(block.samples.col(0).data(), block.samples.col(1).data(), static_cast<int>(n));
}

void MeasurementPipeline::push(std::int64_t first_sample, const double* base, const double* mass,
                               int count) {
  if (count <= 0) return;
  t_scratch_.resize(static_cast<std::size_t>(count));
  const double dt = 1.0 / setup_.sample_rate_hz;
  for (int i = 0; i < count; ++i) {
    t_scratch_[static_cast<std::size_t>(i)] = static_cast<double>(first_sample + i) * dt;
  }
  stream_end_s_ = std::max(stream_end_s_, static_cast<double>(first_sample + count) * dt);
  analyse(base, mass, count);
}

void MeasurementPipeline::analyse(const double* base, const double* mass, int count) {
  completed_.clear();
  analyzer_.push(t_scratch_.data(), base, mass, count, completed_);
  cycle_count_ += completed_.size();
  if (keep_cycles_) cycles_.insert(cycles_.end(), completed_.begin(), completed_.end());
  tracker_.push(completed_, levels_);
}

void MeasurementPipeline::finish() { tracker_.finish(levels_, stream_end_s_); }

}  // namespace oscilab::analysis

#include "daq/live/live_edc.h"

#include <algorithm>
#include <cmath>

namespace oscilab::daq {

void LiveEdc::configure(const analysis::PipelineSettings& settings,
                        const analysis::StreamSetup& stream, std::optional<Excitation> excitation) {
  settings_ = settings;
  stream_ = stream;
  excitation_ = std::move(excitation);
}

void LiveEdc::start(double freq_hz, double t0_s) {
  analysis::StreamSetup setup = stream_;
  setup.excitation_freq_hz = freq_hz;
  setup.t0_s = t0_s;
  // An excitation built in code may leave `extra` null rather than an object.
  setup.windowed_levels = excitation_ && excitation_->extra.is_object() &&
                          excitation_->extra.value("levels_live", false);
  if (excitation_) {  // levels the stream's sidecar gives up front, in stream time
    for (const ExcitationLevel& level : excitation_->levels) {
      if (level.end_s > t0_s)
        setup.level_windows.push_back({level.start_s, level.end_s, level.f0_n});
    }
  }
  // The pipeline keeps no cycles of its own: push() takes each push's new ones.
  pipeline_ = std::make_unique<analysis::MeasurementPipeline>(settings_, setup, false);
  freq_hz_ = freq_hz;
  // What this pipeline has published (the levels before it are in levels_done_).
  levels_seen_ = 0;
}

void LiveEdc::note_arrival(std::uint64_t first_sample, std::uint64_t end_sample,
                           std::chrono::steady_clock::time_point delivered) {
  arrivals_[arrivals_next_] = {first_sample, end_sample, delivered};
  arrivals_next_ = (arrivals_next_ + 1) % kArrivals;
}

void LiveEdc::push(std::uint64_t first_sample, const double* base_si, const double* mass_si,
                   int rows) {
  if (!pipeline_) return;
  pipeline_->push(static_cast<std::int64_t>(first_sample), base_si, mass_si, rows);
  const std::vector<analysis::CycleFit>& completed = pipeline_->last_completed();
  fresh_.insert(fresh_.end(), completed.begin(), completed.end());
}

void LiveEdc::exclude(double from_s, double to_s) {
  if (pipeline_) pipeline_->exclude(from_s, to_s);
}

void LiveEdc::finish() {
  if (pipeline_) pipeline_->finish();
}

void LiveEdc::publish(std::chrono::steady_clock::time_point now, AcquisitionStatus& status) {
  if (!pipeline_) return;
  const bool new_levels = pipeline_->levels().size() != levels_seen_;
  if (fresh_.empty() && !new_levels) return;
  double latency_s = -1.0;
  for (const analysis::CycleFit& cycle : fresh_) {
    const auto start =
        static_cast<std::uint64_t>(std::ceil(cycle.start_s * stream_.sample_rate_hz - 1e-9));
    for (const BlockArrival& a : arrivals_) {
      if (a.end_sample > a.first_sample && start >= a.first_sample && start < a.end_sample) {
        latency_s = std::chrono::duration<double>(now - a.delivered).count();
        if (latencies_s_.size() == kMaxLatencies) latencies_s_.erase(latencies_s_.begin());
        latencies_s_.push_back(latency_s);
        break;
      }
    }
  }
  cycles_.insert(cycles_.end(), fresh_.begin(), fresh_.end());
  cycle_count_ += fresh_.size();
  fresh_.clear();
  while (cycles_.size() > kept_cycles_) cycles_.pop_front();
  if (new_levels) {
    levels_ = levels_done_;
    levels_.insert(levels_.end(), pipeline_->levels().begin(), pipeline_->levels().end());
    levels_seen_ = pipeline_->levels().size();
  }
  current_level_ = pipeline_->current_level();
  status.cycles = static_cast<long>(cycle_count_);
  status.excluded_cycles = pipeline_->excluded_cycles();
  status.levels = levels_.size();
  if (latency_s >= 0) {
    status.edc_latency_s = latency_s;
    status.edc_latency_max_s = std::max(status.edc_latency_max_s, latency_s);
  }
}

void LiveEdc::close_pipeline(AcquisitionStatus& status) {
  publish(std::chrono::steady_clock::now(), status);
  levels_done_.insert(levels_done_.end(), pipeline_->levels().begin(), pipeline_->levels().end());
  levels_ = levels_done_;
  current_level_.reset();
}

void LiveEdc::apply_level(double f0_n, double freq_hz, double change_s, double from_s, double to_s,
                          AcquisitionStatus& status) {
  if (!pipeline_) return;
  if (std::abs(freq_hz - freq_hz_) > 1e-9 * freq_hz_) {
    // A new frequency: a new cycle grid, from the change on.
    pipeline_->finish();
    close_pipeline(status);
    start(freq_hz, change_s);
  }
  // f0 = 0 is the table at rest: it ends the level before it and starts none.
  pipeline_->end_level_window(change_s);
  if (f0_n > 0) pipeline_->add_level_window({from_s, to_s, f0_n});
}

void LiveEdc::publish_finished(AcquisitionStatus& status) {
  if (pipeline_) close_pipeline(status);
}

}  // namespace oscilab::daq

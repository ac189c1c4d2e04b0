#include "daq/live/sample_checker.h"

#include <cmath>

namespace oscilab::daq {

const char* to_string(BadSampleKind kind) {
  return kind == BadSampleKind::NonFinite ? "non-finite" : "saturated";
}

SampleChecker::SampleChecker(std::vector<Channel> channels, int max_rows)
    : channels_(std::move(channels)),
      non_finite_(channels_.size()),
      saturated_(channels_.size()),
      bad_rows_(static_cast<std::size_t>(max_rows > 0 ? max_rows : 0), 0) {}

void SampleChecker::close(OpenRun& run, BadSampleKind kind, int channel, std::vector<Run>& closed) {
  if (!run.open) return;
  closed.push_back({kind, channel, run.from, run.to, run.count});
  run = OpenRun();
}

SampleChecker::Counts SampleChecker::check(const RawBlock& block, std::uint64_t first_sample,
                                           std::vector<Run>& closed) {
  Counts counts;
  const int channels = static_cast<int>(channels_.size());
  if (bad_rows_.size() < static_cast<std::size_t>(block.rows)) {
    bad_rows_.resize(static_cast<std::size_t>(block.rows), 0);  // a larger block than announced
  }
  for (int r = 0; r < block.rows; ++r) {
    const std::uint64_t sample = first_sample + static_cast<std::uint64_t>(r);
    bool row_bad = false;
    for (int c = 0; c < channels && c < block.channels; ++c) {
      const Channel& channel = channels_[static_cast<std::size_t>(c)];
      const double v = block.value(r, c);
      const bool finite = std::isfinite(v);
      const double physical = channel.scale * v + channel.offset;
      const bool saturated =
          finite && channel.range &&
          (physical <= channel.range->first || physical >= channel.range->second);
      const auto track = [&](bool bad, OpenRun& run, BadSampleKind kind) {
        if (bad) {
          if (!run.open) run.open = true, run.from = sample;
          run.to = sample;
          ++run.count;
        } else {
          close(run, kind, c, closed);
        }
      };
      track(!finite, non_finite_[static_cast<std::size_t>(c)], BadSampleKind::NonFinite);
      track(saturated, saturated_[static_cast<std::size_t>(c)], BadSampleKind::Saturated);
      if (!finite) ++counts.non_finite;
      if (saturated) ++counts.saturated;
      row_bad = row_bad || !finite || saturated;
    }
    bad_rows_[static_cast<std::size_t>(r)] = row_bad ? 1 : 0;
  }
  return counts;
}

void SampleChecker::finish(std::vector<Run>& closed) {
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    close(non_finite_[c], BadSampleKind::NonFinite, static_cast<int>(c), closed);
    close(saturated_[c], BadSampleKind::Saturated, static_cast<int>(c), closed);
  }
}

}  // namespace oscilab::daq

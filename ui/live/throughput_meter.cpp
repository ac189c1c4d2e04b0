#include "ui/live/throughput_meter.h"

#include <algorithm>

namespace oscilab::ui {

void ThroughputMeter::add(double wall_s, std::uint64_t samples) {
  if (!readings_.empty() && samples < readings_.back().second) readings_.clear();  // restarted
  readings_.emplace_back(wall_s, samples);
  while (readings_.size() > 2 && wall_s - readings_[1].first >= span_s_) readings_.pop_front();
}

double ThroughputMeter::samples_per_s() const {
  if (readings_.size() < 2) return 0.0;
  const double dt = readings_.back().first - readings_.front().first;
  if (!(dt >= 0.1)) return 0.0;
  return static_cast<double>(readings_.back().second - readings_.front().second) / dt;
}

}  // namespace oscilab::ui

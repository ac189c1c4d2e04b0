#include "daq/recording/sample_overview.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace oscilab::daq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

SampleOverview::SampleOverview(Eigen::Index channels) : channels_(channels), levels_(1) {
  if (channels < 1) throw std::invalid_argument("SampleOverview: no channels");
}

void SampleOverview::add(const Eigen::Ref<const Eigen::MatrixXd>& rows) {
  if (finished_) throw std::logic_error("SampleOverview::add after finish");
  if (rows.cols() != channels_) throw std::invalid_argument("SampleOverview::add: channel count");
  Level& level = levels_[0];
  for (Eigen::Index r = 0; r < rows.rows(); ++r) {
    if (in_bucket_ == 0) {
      level.min.resize(level.min.size() + std::size_t(channels_), kNaN);
      level.max.resize(level.max.size() + std::size_t(channels_), kNaN);
    }
    const std::size_t at = level.min.size() - std::size_t(channels_);
    for (Eigen::Index c = 0; c < channels_; ++c) {
      const double value = rows(r, c);  // fmin/fmax leave a NaN out
      level.min[at + std::size_t(c)] = std::fmin(level.min[at + std::size_t(c)], value);
      level.max[at + std::size_t(c)] = std::fmax(level.max[at + std::size_t(c)], value);
    }
    if (++in_bucket_ == kFinestBucket) in_bucket_ = 0;
  }
  samples_ += rows.rows();
}

void SampleOverview::finish() {
  if (finished_) return;
  finished_ = true;
  const auto ch = std::size_t(channels_);
  for (;;) {
    const Level& fine = levels_.back();
    const std::size_t buckets = fine.min.size() / ch;
    if (buckets <= 1) break;
    Level coarse;
    const std::size_t coarse_buckets = (buckets + 1) / 2;
    coarse.min.resize(coarse_buckets * ch);
    coarse.max.resize(coarse_buckets * ch);
    for (std::size_t b = 0; b < coarse_buckets; ++b) {
      for (std::size_t c = 0; c < ch; ++c) {
        const std::size_t left = 2 * b * ch + c;
        const bool pair = 2 * b + 1 < buckets;
        coarse.min[b * ch + c] =
            pair ? std::fmin(fine.min[left], fine.min[left + ch]) : fine.min[left];
        coarse.max[b * ch + c] =
            pair ? std::fmax(fine.max[left], fine.max[left + ch]) : fine.max[left];
      }
    }
    levels_.push_back(std::move(coarse));
  }
  for (Level& level : levels_) {
    level.min.shrink_to_fit();
    level.max.shrink_to_fit();
  }
}

Eigen::Index SampleOverview::bucket_samples_for(Eigen::Index first, Eigen::Index end,
                                                Eigen::Index max_buckets) const {
  if (!finished_) throw std::logic_error("SampleOverview::bucket_samples_for before finish");
  first = std::clamp<Eigen::Index>(first, 0, samples_);
  end = std::clamp<Eigen::Index>(end, first + 1, std::max<Eigen::Index>(samples_, first + 1));
  max_buckets = std::max<Eigen::Index>(max_buckets, 1);
  std::size_t level = 0;
  Eigen::Index size = kFinestBucket;
  while (level + 1 < levels_.size() && (end - 1) / size - first / size + 1 > max_buckets) {
    ++level;
    size *= 2;
  }
  return size;
}

SampleOverview::Envelope SampleOverview::envelope(Eigen::Index channel, Eigen::Index first,
                                                  Eigen::Index end,
                                                  Eigen::Index bucket_samples) const {
  if (!finished_) throw std::logic_error("SampleOverview::envelope before finish");
  if (channel < 0 || channel >= channels_) {
    throw std::out_of_range("SampleOverview::envelope: channel");
  }
  std::size_t level = 0;
  while (level + 1 < levels_.size() && (kFinestBucket << level) < bucket_samples) ++level;
  const Eigen::Index size = kFinestBucket << level;
  if (size != bucket_samples)
    throw std::invalid_argument("SampleOverview::envelope: no such level");
  Envelope out;
  first = std::clamp<Eigen::Index>(first, 0, samples_);
  end = std::clamp<Eigen::Index>(end, first, samples_);
  if (end == first) return out;
  const Level& l = levels_[level];
  const auto ch = std::size_t(channels_);
  const Eigen::Index b0 = first / size;
  const Eigen::Index b1 = (end - 1) / size;
  out.bucket_samples = size;
  out.first_sample = b0 * size;
  out.min.reserve(std::size_t(b1 - b0 + 1));
  out.max.reserve(std::size_t(b1 - b0 + 1));
  for (Eigen::Index b = b0; b <= b1; ++b) {
    out.min.push_back(l.min[std::size_t(b) * ch + std::size_t(channel)]);
    out.max.push_back(l.max[std::size_t(b) * ch + std::size_t(channel)]);
  }
  return out;
}

double SampleOverview::max_abs(Eigen::Index channel) const {
  if (!finished_) throw std::logic_error("SampleOverview::max_abs before finish");
  const Level& top = levels_.back();
  const auto ch = std::size_t(channels_);
  double largest = 0.0;
  for (std::size_t b = 0; b < top.min.size() / ch; ++b) {
    const double lo = top.min[b * ch + std::size_t(channel)];
    const double hi = top.max[b * ch + std::size_t(channel)];
    if (std::isfinite(lo)) largest = std::max(largest, std::abs(lo));
    if (std::isfinite(hi)) largest = std::max(largest, std::abs(hi));
  }
  return largest;
}

}  // namespace oscilab::daq

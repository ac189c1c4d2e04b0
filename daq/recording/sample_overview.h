#pragma once

#include <vector>

#include <Eigen/Core>

namespace oscilab::daq {

/// A min/max pyramid of a recording's channels, for drawing a record of any length: level 0 holds
/// the least and the greatest value of each bucket of kFinestBucket samples, each coarser level
/// those of two buckets of the level below. A plot of a time window draws the finest level with
/// no more buckets in the window than it has pixels to spare, so a day-long record (44 M samples
/// per channel at 512 Hz) is drawn from a few thousand points, and its pyramid takes about 32 B
/// per 64 samples per channel (11 MB per channel for the day).
///
/// Non-finite samples (the invalid intervals of a live recording) are left out of their buckets'
/// extremes; a bucket of nothing but such samples is NaN at both ends, a gap in the curve.
class SampleOverview {
 public:
  /// Samples per bucket at level 0: a window of up to 64 times the plot's width in pixels is
  /// drawn from level 0 or the samples themselves.
  static constexpr Eigen::Index kFinestBucket = 64;

  explicit SampleOverview(Eigen::Index channels);

  /// Adds the next samples, in time order: one row per sample, one column per channel (SI).
  void add(const Eigen::Ref<const Eigen::MatrixXd>& rows);
  /// Closes the last, partial bucket and builds the coarser levels. Call once, after the last add.
  void finish();

  Eigen::Index channel_count() const { return channels_; }
  Eigen::Index sample_count() const { return samples_; }

  /// A channel's extremes over buckets: bucket k covers the samples from
  /// first_sample + k·bucket_samples on, bucket_samples of them (fewer for the record's last).
  struct Envelope {
    Eigen::Index bucket_samples = 0;
    Eigen::Index first_sample = 0;
    std::vector<double> min, max;
  };
  /// The bucket size of the finest level that covers samples [first, end) in at most
  /// `max_buckets` buckets (at least 1), from the bucket holding `first` to the one holding
  /// end − 1; the coarsest level's when none does. The range is clipped to the record.
  Eigen::Index bucket_samples_for(Eigen::Index first, Eigen::Index end,
                                  Eigen::Index max_buckets) const;
  /// The buckets of the level of `bucket_samples` (kFinestBucket · 2^k, as bucket_samples_for
  /// gives) over samples [first, end) of `channel`, from the bucket holding `first` to the one
  /// holding end − 1. The range is clipped to the record; an empty one gives an empty envelope.
  Envelope envelope(Eigen::Index channel, Eigen::Index first, Eigen::Index end,
                    Eigen::Index bucket_samples) const;

  /// The largest |value| of a channel over the whole record (0 when none is finite).
  double max_abs(Eigen::Index channel) const;

  /// Levels built (1 + log2 of the level-0 bucket count, rounded up); for tests.
  int level_count() const { return static_cast<int>(levels_.size()); }

 private:
  struct Level {  // bucket-major: bucket b of channel c at b * channels + c
    std::vector<double> min, max;
  };

  Eigen::Index channels_;
  Eigen::Index samples_ = 0;
  Eigen::Index in_bucket_ = 0;  // samples of the open bucket of level 0
  std::vector<Level> levels_;   // levels_[0] is being filled until finish()
  bool finished_ = false;
};

}  // namespace oscilab::daq

#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

namespace oscilab::analysis {

/// One pass over a record's two motion channels, in SI, from its first sample on.
class ChannelReader {
 public:
  virtual ~ChannelReader() = default;
  /// Reads up to `count` next samples of each channel into `base` and `mass`; returns how many
  /// were read (fewer only at the record's end). Throws InputError naming the file and the
  /// sample for a value it cannot give (a non-finite sample the record does not declare
  /// invalid, a file shorter than its header says).
  virtual Eigen::Index read(double* base, double* mass, Eigen::Index count) = 0;
};

/// A record's samples where they live: in a file, read a pass at a time, so that a record of
/// any length is analysed in bounded memory (MeasurementChannels::source). Each open() is an
/// independent pass, so passes may run on different threads.
class ChannelSource {
 public:
  virtual ~ChannelSource() = default;
  /// Samples per channel.
  virtual Eigen::Index sample_count() const = 0;
  virtual std::unique_ptr<ChannelReader> open() const = 0;
};

/// Reads exactly `count` next samples of each channel, or throws InputError naming
/// `record_name`: a source that ends before the sample count it stated is a broken file.
void read_samples(ChannelReader& reader, double* base, double* mass, Eigen::Index count,
                  const std::string& record_name);

/// A pass over channels in memory (two arrays of `count` samples, which must outlive it).
class MemoryChannelReader final : public ChannelReader {
 public:
  MemoryChannelReader(const double* base, const double* mass, Eigen::Index count)
      : base_(base), mass_(mass), count_(count) {}
  Eigen::Index read(double* base, double* mass, Eigen::Index count) override;

 private:
  const double* base_;
  const double* mass_;
  Eigen::Index count_;
  Eigen::Index next_ = 0;
};

}  // namespace oscilab::analysis

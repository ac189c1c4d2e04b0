#include "analysis/pipeline/channel_source.h"

#include <algorithm>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

void read_samples(ChannelReader& reader, double* base, double* mass, Eigen::Index count,
                  const std::string& record_name) {
  const Eigen::Index got = reader.read(base, mass, count);
  if (got != count) {
    throw InputError(record_name + ": the record ended " + std::to_string(count - got) +
                     " samples before the length it stated");
  }
}

Eigen::Index MemoryChannelReader::read(double* base, double* mass, Eigen::Index count) {
  const Eigen::Index n = std::clamp<Eigen::Index>(count_ - next_, 0, count);
  std::copy(base_ + next_, base_ + next_ + n, base);
  std::copy(mass_ + next_, mass_ + next_ + n, mass);
  next_ += n;
  return n;
}

}  // namespace oscilab::analysis

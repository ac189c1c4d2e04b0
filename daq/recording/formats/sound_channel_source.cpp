// A sound container's base and mass channels read a pass at a time (sound_file.h).
#include <limits>
#include <optional>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/signal/ac_coupling.h"
#include "daq/recording/formats/sound_file.h"

namespace oscilab::daq {
namespace {

class SoundChannelReader final : public analysis::ChannelReader {
 public:
  SoundChannelReader(std::string path, const Sidecar& sidecar, const std::string& sidecar_name,
                     ChannelCalibration base, ChannelCalibration mass)
      : path_(std::move(path)),
        sidecar_(sidecar),
        open_(open_sound_file(path_, sidecar, sidecar_name)),
        base_(std::move(base)),
        mass_(std::move(mass)) {
    base_inverse_ = coupling_inverse(base_, sidecar_, path_);
    mass_inverse_ = coupling_inverse(mass_, sidecar_, path_);
  }

  Eigen::Index read(double* base, double* mass, Eigen::Index count) override {
    const int channels = open_.info.channels;
    Eigen::Index done = 0;
    while (done < count) {
      const sf_count_t wanted = std::min<sf_count_t>(kBlockFrames, count - done);
      frames_.resize(static_cast<std::size_t>(wanted * channels));
      const sf_count_t got = sf_readf_double(open_.file.get(), frames_.data(), wanted);
      if (got <= 0) break;
      for (sf_count_t f = 0; f < got; ++f) {
        const double* frame = frames_.data() + f * channels;
        base[done] =
            calibrated_sample(base_, base_inverse_, frame[base_.column], sidecar_, row_, path_);
        mass[done] =
            calibrated_sample(mass_, mass_inverse_, frame[mass_.column], sidecar_, row_, path_);
        ++done;
        ++row_;
      }
    }
    if (sf_error(open_.file.get()) != SF_ERR_NO_ERROR) {
      throw InputError(path_ + ": cannot read the samples: " + sf_strerror(open_.file.get()));
    }
    if (done < count && row_ < open_.info.frames) {
      throw InputError(truncated_sound_message(path_, open_.info.frames, row_));
    }
    return done;
  }

 private:
  static constexpr sf_count_t kBlockFrames = 8192;

  std::string path_;
  Sidecar sidecar_;
  OpenSoundFile open_;
  ChannelCalibration base_, mass_;
  std::optional<analysis::AcCouplingInverse> base_inverse_, mass_inverse_;
  std::vector<double> frames_;
  Eigen::Index row_ = 0;
};

class SoundChannelSource final : public analysis::ChannelSource {
 public:
  SoundChannelSource(std::string path, Sidecar sidecar, std::string sidecar_name,
                     Eigen::Index frames, int base_column, int mass_column)
      : path_(std::move(path)),
        sidecar_(std::move(sidecar)),
        sidecar_name_(std::move(sidecar_name)),
        frames_(frames),
        base_(calibration_of(sidecar_, base_column, path_)),
        mass_(calibration_of(sidecar_, mass_column, path_)) {}

  Eigen::Index sample_count() const override { return frames_; }
  std::unique_ptr<analysis::ChannelReader> open() const override {
    return std::make_unique<SoundChannelReader>(path_, sidecar_, sidecar_name_, base_, mass_);
  }

 private:
  std::string path_;
  Sidecar sidecar_;
  std::string sidecar_name_;
  Eigen::Index frames_;
  ChannelCalibration base_, mass_;
};

}  // namespace

std::shared_ptr<const analysis::ChannelSource> sound_channel_source(const std::string& path,
                                                                    const Sidecar& sidecar,
                                                                    const std::string& sidecar_name,
                                                                    int base_column,
                                                                    int mass_column) {
  const OpenSoundFile open = open_sound_file(path, sidecar, sidecar_name);
  const sf_count_t frames = open.info.frames;
  if (frames == std::numeric_limits<sf_count_t>::max() || frames < 0) return nullptr;
  if (frames == 0) throw InputError(path + ": no samples (empty recording)");
  return std::make_shared<SoundChannelSource>(path, sidecar, sidecar_name, frames, base_column,
                                              mass_column);
}

}  // namespace oscilab::daq

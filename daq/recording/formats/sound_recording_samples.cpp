// Every channel of a sound container read a window at a time (sound_file.h), and the calibration
// the streamed readers share.
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/sound_file.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/recording/opened_recording.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {

ChannelCalibration calibration_of(const Sidecar& sidecar, int column, const std::string& path) {
  const ChannelInfo& channel = sidecar.channels[static_cast<std::size_t>(column)];
  return {column,
          channel.name,
          channel.scale,
          channel.offset,
          unit_to_si(channel.unit, channel.quantity, path),
          channel.ac_coupling_hz};
}

std::optional<analysis::AcCouplingInverse> coupling_inverse(const ChannelCalibration& c,
                                                            const Sidecar& sidecar,
                                                            const std::string& path) {
  if (!c.ac_coupling_hz) return std::nullopt;
  return analysis::AcCouplingInverse(*c.ac_coupling_hz, sidecar.sample_rate_hz,
                                     path + ": channel " + in_quotes(c.name));
}

double calibrated_sample(const ChannelCalibration& c,
                         std::optional<analysis::AcCouplingInverse>& inverse, double stored,
                         const Sidecar& sidecar, Eigen::Index row, const std::string& path) {
  double si = (c.scale * stored + c.offset) * c.unit_factor;
  if (!std::isfinite(si) && !declared_invalid(sidecar, row)) {
    const std::string problem = std::isnan(stored)   ? "is NaN"
                                : std::isinf(stored) ? "is infinite"
                                                     : "(" + number_text(stored) +
                                                           ") overflows after calibration (scale " +
                                                           number_text(c.scale) + ")";
    throw InputError(path + ": channel " + in_quotes(c.name) + ": " +
                     sample_place(row, sidecar.sample_rate_hz, StoredSamples()) + " " + problem);
  }
  if (inverse) si = inverse->push(si);
  return si;
}

namespace {

class SoundRecordingSamples final : public RecordingSamples {
 public:
  SoundRecordingSamples(std::string path, Sidecar sidecar, std::string sidecar_name,
                        OpenSoundFile open)
      : path_(std::move(path)),
        sidecar_(std::move(sidecar)),
        sidecar_name_(std::move(sidecar_name)),
        open_(std::move(open)),
        frames_(open_.info.frames) {
    for (int c = 0; c < open_.info.channels; ++c) {
      calibrations_.push_back(calibration_of(sidecar_, c, path_));
      coupled_ = coupled_ || calibrations_.back().ac_coupling_hz.has_value();
    }
  }

  Eigen::Index sample_count() const override { return frames_; }
  Eigen::Index channel_count() const override { return Eigen::Index(calibrations_.size()); }

  Eigen::MatrixXd read(Eigen::Index first, Eigen::Index count) const override {
    first = std::clamp<Eigen::Index>(first, 0, frames_);
    const Eigen::Index end = first + std::clamp<Eigen::Index>(count, 0, frames_ - first);
    Eigen::MatrixXd out(end - first, channel_count());
    const std::lock_guard lock(mutex_);
    // An AC-coupled channel's inverse is a recursion over every sample before: resume it from
    // the last state kept at or before `first`, keeping the states passed on the way.
    Eigen::Index from = first;
    Inverses inverses(calibrations_.size());
    if (coupled_) {
      const auto wanted = std::size_t(first / kStateEvery);
      if (states_.empty()) {
        for (std::size_t c = 0; c < calibrations_.size(); ++c) {
          inverses[c] = coupling_inverse(calibrations_[c], sidecar_, path_);
        }
        states_.push_back(inverses);
      }
      const std::size_t start = std::min(wanted, states_.size() - 1);
      from = Eigen::Index(start) * kStateEvery;
      inverses = states_[start];
    }
    decode(from, end, inverses, out, first);
    return out;
  }

  analysis::MeasurementChannels measurement_channels() const override {
    return streamed_measurement_channels(path_);
  }

  Recording whole() const override { return read_recording(path_); }

 private:
  using Inverses = std::vector<std::optional<analysis::AcCouplingInverse>>;
  static constexpr Eigen::Index kStateEvery = 4096;
  static constexpr sf_count_t kBlockFrames = 8192;

  // Decodes rows [from, end), calibrating each; rows from `keep_from` on go to `out`. Called
  // with the mutex held.
  void decode(Eigen::Index from, Eigen::Index end, Inverses& inverses, Eigen::MatrixXd& out,
              Eigen::Index keep_from) const {
    const int channels = open_.info.channels;
    if (position_ != from) {
      if (sf_seek(open_.file.get(), from, SEEK_SET) != from) {
        position_ = -1;
        throw InputError(path_ + ": cannot seek to sample " + std::to_string(from) + ": " +
                         sf_strerror(open_.file.get()));
      }
      position_ = from;
    }
    Eigen::Index row = from;
    while (row < end) {
      const sf_count_t wanted = std::min<sf_count_t>(kBlockFrames, end - row);
      block_.resize(std::size_t(wanted * channels));
      const sf_count_t got = sf_readf_double(open_.file.get(), block_.data(), wanted);
      if (got <= 0) break;
      for (sf_count_t f = 0; f < got; ++f, ++row) {
        if (coupled_ && row % kStateEvery == 0 &&
            std::size_t(row / kStateEvery) == states_.size()) {
          states_.push_back(inverses);
        }
        const double* frame = block_.data() + f * channels;
        for (int c = 0; c < channels; ++c) {
          const double si =
              calibrated_sample(calibrations_[std::size_t(c)], inverses[std::size_t(c)], frame[c],
                                sidecar_, row, path_);
          if (row >= keep_from) out(row - keep_from, c) = si;
        }
      }
    }
    position_ = row;
    if (sf_error(open_.file.get()) != SF_ERR_NO_ERROR) {
      position_ = -1;
      throw InputError(path_ + ": cannot read the samples: " + sf_strerror(open_.file.get()));
    }
    if (row < end) throw InputError(truncated_sound_message(path_, frames_, row));
  }

  std::string path_;
  Sidecar sidecar_;
  std::string sidecar_name_;
  OpenSoundFile open_;
  Eigen::Index frames_;
  std::vector<ChannelCalibration> calibrations_;
  bool coupled_ = false;
  mutable std::mutex mutex_;
  mutable Eigen::Index position_ = 0;     // the file's read position, -1 after a failure
  mutable std::vector<Inverses> states_;  // the inverses' state before row k·kStateEvery
  mutable std::vector<double> block_;
};

}  // namespace

std::optional<OpenedRecording> open_sound_for_review(const std::string& path,
                                                     const Sidecar& sidecar,
                                                     const std::string& sidecar_name,
                                                     const OpeningControl& control) {
  OpenSoundFile open = open_sound_file(path, sidecar, sidecar_name);
  const sf_count_t frames = open.info.frames;
  if (frames == std::numeric_limits<sf_count_t>::max() || frames < 0) return std::nullopt;
  if (frames == 0) throw InputError(path + ": no samples (empty recording)");
  OpenedRecording opened;
  opened.sidecar = sidecar;
  opened.source_path = path;
  opened.container = sound_container_name(open.info.format);
  opened.samples =
      std::make_shared<SoundRecordingSamples>(path, sidecar, sidecar_name, std::move(open));
  opened.overview =
      std::make_shared<const SampleOverview>(build_overview(*opened.samples, control));
  return opened;
}

}  // namespace oscilab::daq

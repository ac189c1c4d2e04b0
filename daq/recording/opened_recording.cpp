#include "daq/recording/opened_recording.h"

#include <algorithm>

#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/formats/sound_file.h"
#include "daq/recording/measurement_mapping.h"

namespace oscilab::daq {
namespace {

// Samples read whole: a recording in memory, in SI (what the files stored is not kept: the review
// never sends it on).
class MemoryRecordingSamples final : public RecordingSamples {
 public:
  explicit MemoryRecordingSamples(Recording recording) : recording_(std::move(recording)) {
    recording_.samples_stored.resize(0, 0);
  }
  Eigen::Index sample_count() const override { return recording_.samples_si.rows(); }
  Eigen::Index channel_count() const override { return recording_.samples_si.cols(); }
  Eigen::MatrixXd read(Eigen::Index first, Eigen::Index count) const override {
    first = std::clamp<Eigen::Index>(first, 0, sample_count());
    count = std::clamp<Eigen::Index>(count, 0, sample_count() - first);
    return recording_.samples_si.middleRows(first, count);
  }
  analysis::MeasurementChannels measurement_channels() const override {
    return daq::measurement_channels(recording_);
  }
  Recording whole() const override { return recording_; }

 private:
  Recording recording_;
};

}  // namespace

double OpenedRecording::duration_s() const {
  return sidecar.sample_rate_hz > 0.0 ? double(sample_count()) / sidecar.sample_rate_hz : 0.0;
}

SampleOverview build_overview(const RecordingSamples& samples, const OpeningControl& control) {
  // Windows of 2^16 samples: a multiple of the finest bucket, and a few MB of all channels.
  constexpr Eigen::Index kWindow = Eigen::Index{1} << 16;
  static_assert(kWindow % SampleOverview::kFinestBucket == 0);
  SampleOverview overview(std::max<Eigen::Index>(samples.channel_count(), 1));
  const Eigen::Index count = samples.sample_count();
  if (samples.channel_count() > 0) {
    for (Eigen::Index first = 0; first < count; first += kWindow) {
      if (control.cancel.cancelled()) throw OpeningCancelled();
      if (control.progress) control.progress(double(first) / double(count));
      overview.add(samples.read(first, kWindow));
    }
  }
  if (control.cancel.cancelled()) throw OpeningCancelled();
  overview.finish();
  if (control.progress) control.progress(1.0);
  return overview;
}

OpenedRecording hold_recording(Recording recording, const OpeningControl& control) {
  OpenedRecording opened;
  opened.sidecar = recording.sidecar;
  opened.source_path = recording.source_path;
  opened.container = recording.container;
  opened.samples = std::make_shared<MemoryRecordingSamples>(std::move(recording));
  opened.overview =
      std::make_shared<const SampleOverview>(build_overview(*opened.samples, control));
  return opened;
}

OpenedRecording open_recording_for_review(const std::string& path, const OpeningControl& control) {
  const RecordingFile file = open_recording_file(path);
  if (file.format == &sound_format()) {
    if (std::optional<OpenedRecording> opened =
            open_sound_for_review(path, file.sidecar, file.sidecar_path, control)) {
      return std::move(*opened);
    }
  }
  if (control.progress) control.progress(0.0);
  // The read's share of the progress first, then the overview's pass over the samples in memory.
  OpeningControl reading{nullptr, control.cancel};
  if (control.progress) {
    reading.progress = [&control](double f) { control.progress(kReadShare * f); };
  }
  Recording recording =
      file.format->read_controlled(path, file.sidecar, file.sidecar_path, reading);
  OpeningControl overview{nullptr, control.cancel};
  if (control.progress) {
    overview.progress = [&control](double f) {
      control.progress(kReadShare + (1.0 - kReadShare) * f);
    };
  }
  return hold_recording(std::move(recording), overview);
}

}  // namespace oscilab::daq

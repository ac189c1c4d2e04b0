#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <sndfile.h>

#include "analysis/pipeline/channel_source.h"
#include "analysis/signal/ac_coupling.h"
#include "daq/recording/opened_recording.h"
#include "daq/recording/sidecar.h"

// What the sound-container reader and its streamed channels share (sound_format.cpp,
// sound_channel_source.cpp).
namespace oscilab::daq {

struct SndfileCloser {
  void operator()(SNDFILE* file) const { sf_close(file); }
};
using SndfileHandle = std::unique_ptr<SNDFILE, SndfileCloser>;

struct OpenSoundFile {
  SndfileHandle file;
  SF_INFO info{};
};

/// Opens a sound container for reading its samples as the sidecar maps them: the channel count
/// and rate checked against the sidecar (named `sidecar_name`), a truncation libsndfile only
/// logs refused, integers read as their counts. Throws InputError naming the file.
OpenSoundFile open_sound_file(const std::string& path, const Sidecar& sidecar,
                              const std::string& sidecar_name);

/// The container and its encoding as libsndfile names them: "WAV (Microsoft), 64 bit float".
std::string sound_container_name(int format);

/// "PATH: truncated: the header promises N samples per channel, the file holds M (...)".
std::string truncated_sound_message(const std::string& path, std::int64_t promised,
                                    std::int64_t held);

/// One channel's calibration into SI, as calibrate() applies it (stored_samples.h).
struct ChannelCalibration {
  int column = 0;
  std::string name;
  double scale = 1.0, offset = 0.0, unit_factor = 1.0;
  std::optional<double> ac_coupling_hz;
};
ChannelCalibration calibration_of(const Sidecar& sidecar, int column, const std::string& path);
/// The inverse of the channel's input high-pass, when the sidecar states one.
std::optional<analysis::AcCouplingInverse> coupling_inverse(const ChannelCalibration& c,
                                                            const Sidecar& sidecar,
                                                            const std::string& path);
/// physical = scale × stored + offset in the channel's unit, then × unit factor → SI, then the
/// input's high-pass undone as the live chain does. Throws InputError naming `path`, the channel
/// and sample `row` for a non-finite value outside the sidecar's invalid intervals.
double calibrated_sample(const ChannelCalibration& c,
                         std::optional<analysis::AcCouplingInverse>& inverse, double stored,
                         const Sidecar& sidecar, Eigen::Index row, const std::string& path);

/// The base and mass channels (0-based columns of the file) of a sound container, streamed: each
/// pass decodes the file from its start and calibrates as the reader does (calibrate()), so a
/// record of any length is analysed in bounded memory. Null when the file does not state its
/// length (the caller reads it whole). Throws InputError as the reader does for what the header
/// shows; a pass throws for a non-finite sample outside the sidecar's invalid intervals and for
/// a file shorter than its header.
std::shared_ptr<const analysis::ChannelSource> sound_channel_source(const std::string& path,
                                                                    const Sidecar& sidecar,
                                                                    const std::string& sidecar_name,
                                                                    int base_column,
                                                                    int mass_column);

/// A sound container opened to be looked at (opened_recording.h): its channels stay in the file,
/// read a window at a time by seeking and calibrated as the reader calibrates (an AC-coupled
/// channel's inverse resumed from a state kept every 4096 samples, so a window equals the rows
/// read_recording gives); one pass builds the overview and checks every sample. Nothing when the
/// file does not state its length (the caller reads it whole). Throws InputError for a
/// non-finite sample outside the sidecar's invalid intervals and for a file shorter than its
/// header, then and in any later read; OpeningCancelled when `control` is cancelled during the
/// overview's pass.
std::optional<OpenedRecording> open_sound_for_review(const std::string& path,
                                                     const Sidecar& sidecar,
                                                     const std::string& sidecar_name,
                                                     const OpeningControl& control = {});

}  // namespace oscilab::daq

#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <sndfile.h>

#include "analysis/pipeline/channel_source.h"
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

/// "PATH: truncated: the header promises N samples per channel, the file holds M (...)".
std::string truncated_sound_message(const std::string& path, std::int64_t promised,
                                    std::int64_t held);

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

}  // namespace oscilab::daq

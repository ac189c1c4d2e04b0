// Sound containers through libsndfile: read (the sidecar's channels are the file's channels in
// order, integer formats as their counts) and written (64-bit float, or 24-bit FLAC).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <sstream>
#include <string_view>
#include <system_error>

#include <sndfile.h>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/formats/sound_file.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

std::string sndfile_format_name(int format) {
  SF_FORMAT_INFO info{};
  info.format = format;
  if (sf_command(nullptr, SFC_GET_FORMAT_INFO, &info, sizeof info) != 0 || info.name == nullptr) {
    return "format 0x" + [&] {
      char buffer[16];
      std::snprintf(buffer, sizeof buffer, "%x", static_cast<unsigned>(format));
      return std::string(buffer);
    }();
  }
  return info.name;
}

// libsndfile shortens a truncated WAV/W64/RF64/AIFF/CAF silently to the bytes present and only
// logs it: "data : 16000 (should be 14997)". Find that line; sizes 0 and 0xFFFFFFFF are the
// placeholders of streaming writers, not truncation.
std::string truncation_in_log(SNDFILE* file) {
  std::vector<char> log(16384, '\0');
  sf_command(file, SFC_GET_LOG_INFO, log.data(), static_cast<int>(log.size()) - 1);
  std::istringstream lines(std::string(log.data()));
  std::string line;
  while (std::getline(lines, line)) {
    const auto start = line.find_first_not_of(' ');
    if (start == std::string::npos) continue;
    const std::string_view text(line.c_str() + start);
    if (text.rfind("data", 0) != 0 && text.rfind("SSND", 0) != 0) continue;
    const auto colon = text.find(':');
    const auto should = text.find("(should be ");
    if (colon == std::string_view::npos || should == std::string_view::npos) continue;
    const long long declared =
        std::strtoll(std::string(text.substr(colon + 1)).c_str(), nullptr, 10);
    const long long present =
        std::strtoll(std::string(text.substr(should + 11)).c_str(), nullptr, 10);
    if (declared <= present || declared == 0 || declared == 0xFFFFFFFFLL) continue;
    return "truncated: the header promises " + std::to_string(declared) +
           " bytes of samples, the file holds " + std::to_string(present) +
           " (oscilab-cli recover keeps the whole samples it holds)";
  }
  return "";
}

}  // namespace

std::string sound_container_name(int format) {
  return sndfile_format_name(format & SF_FORMAT_TYPEMASK) + ", " +
         sndfile_format_name(format & SF_FORMAT_SUBMASK);
}

OpenSoundFile open_sound_file(const std::string& path, const Sidecar& sidecar,
                              const std::string& sidecar_name) {
  OpenSoundFile open;
  open.file.reset(sf_open(path.c_str(), SFM_READ, &open.info));
  const SF_INFO& info = open.info;
  if (!open.file) {
    throw InputError(path + ": not a sound file libsndfile can read (" + sf_strerror(nullptr) +
                     ")");
  }
  const auto channels = static_cast<int>(sidecar.channels.size());
  if (info.channels != channels) {
    throw InputError(path + ": the file holds " + std::to_string(info.channels) + " channels, " +
                     sidecar_name + " lists " + std::to_string(channels));
  }
  // The container stores an integer rate; the sidecar's (possibly measured, fractional) rate
  // must round to it.
  if (!(std::abs(sidecar.sample_rate_hz - info.samplerate) < 0.5)) {
    throw InputError(path + ": the file's sample rate is " + std::to_string(info.samplerate) +
                     " Hz, " + sidecar_name + " says " + number_text(sidecar.sample_rate_hz) +
                     " Hz");
  }
  if (const std::string truncation = truncation_in_log(open.file.get()); !truncation.empty()) {
    throw InputError(path + ": " + truncation);
  }
  // Integer formats read as their integer counts, not normalised to ±1 (see ChannelInfo).
  sf_command(open.file.get(), SFC_SET_NORM_DOUBLE, nullptr, SF_FALSE);
  return open;
}

std::string truncated_sound_message(const std::string& path, std::int64_t promised,
                                    std::int64_t held) {
  return path + ": truncated: the header promises " + std::to_string(promised) +
         " samples per channel, the file holds " + std::to_string(held) +
         " (oscilab-cli recover keeps the whole samples it holds)";
}

namespace {

Recording read_sound(const std::string& path, const Sidecar& sidecar,
                     const std::string& sidecar_name) {
  OpenSoundFile open = open_sound_file(path, sidecar, sidecar_name);
  SndfileHandle& file = open.file;
  const SF_INFO& info = open.info;
  const auto channels = static_cast<int>(sidecar.channels.size());

  StoredSamples stored;
  constexpr sf_count_t kBlockFrames = 8192;
  std::vector<double> block(static_cast<std::size_t>(kBlockFrames) * channels);
  // The header's frame count sizes the samples at once, up to what the file's bytes can hold
  // (a header that claims more does not reserve memory for it: a truncated file fails below,
  // and a file that decodes to more, as a near-constant FLAC signal can, grows the vector).
  if (info.frames > 0 && info.frames != std::numeric_limits<sf_count_t>::max()) {
    std::error_code error;
    const std::uintmax_t bytes = std::filesystem::file_size(path, error);
    constexpr std::uintmax_t kMaxSamplesPerByte = 64;
    const std::uintmax_t claimed = static_cast<std::uintmax_t>(info.frames) * channels;
    if (!error) stored.values.reserve(std::min(claimed, kMaxSamplesPerByte * bytes));
  }
  sf_count_t frames = 0;
  for (;;) {
    const sf_count_t got = sf_readf_double(file.get(), block.data(), kBlockFrames);
    if (got <= 0) break;
    stored.values.insert(stored.values.end(), block.begin(), block.begin() + got * channels);
    frames += got;
  }
  if (sf_error(file.get()) != SF_ERR_NO_ERROR) {
    throw InputError(path + ": cannot read the samples: " + sf_strerror(file.get()));
  }
  if (frames == 0) throw InputError(path + ": no samples (empty recording)");
  if (info.frames != std::numeric_limits<sf_count_t>::max() && frames < info.frames) {
    throw InputError(truncated_sound_message(path, info.frames, frames));
  }

  Recording recording;
  recording.sidecar = sidecar;
  recording.samples_si = calibrate(stored, sidecar, path);
  recording.samples_stored = as_matrix(stored, recording.samples_si.cols());
  recording.source_path = path;
  recording.container = sound_container_name(info.format);
  return recording;
}

class SoundFormat final : public FormatReader {
 public:
  std::string_view format_name() const override { return "sound containers (libsndfile)"; }

  bool matches_signature(std::string_view head) const override {
    // RIFF/RIFX (WAV), RF64, FORM (AIFF), caff (CAF), fLaC, and W64's "riff" GUID.
    for (const std::string_view magic :
         {"RIFF", "RIFX", "RF64", "BW64", "FORM", "caff", "fLaC", "riff", "OggS"}) {
      if (head.substr(0, magic.size()) == magic) return true;
    }
    return false;
  }

  bool matches_extension(std::string_view extension) const override {
    for (const std::string_view known : {".wav", ".flac", ".w64", ".rf64", ".aif", ".aiff", ".aifc",
                                         ".caf", ".ogg", ".au", ".snd"}) {
      if (extension == known) return true;
    }
    return false;
  }

  FileContents describe(const std::string& path) const override {
    SF_INFO info{};
    SndfileHandle file(sf_open(path.c_str(), SFM_READ, &info));
    if (!file) {
      throw InputError(path + ": not a sound file libsndfile can read (" + sf_strerror(nullptr) +
                       ")");
    }
    FileContents contents;
    contents.container = sound_container_name(info.format);
    contents.picked_by_source = false;
    for (int c = 0; c < info.channels; ++c) {
      FileSignal signal;
      signal.name = "channel " + std::to_string(c + 1);
      signal.sample_count = info.frames;
      signal.sample_rate_hz = static_cast<double>(info.samplerate);
      signal.stored_type = sndfile_format_name(info.format & SF_FORMAT_SUBMASK);
      contents.file_signals.push_back(std::move(signal));
    }
    return contents;
  }

  Recording read(const std::string& path, const Sidecar& sidecar,
                 const std::string& sidecar_name) const override {
    return read_sound(path, sidecar, sidecar_name);
  }
};

}  // namespace

const FormatReader& sound_format() {
  static const SoundFormat format;
  return format;
}

int sound_format_for(const std::string& extension) {
  if (extension == ".wav") return SF_FORMAT_WAV | SF_FORMAT_DOUBLE;
  if (extension == ".w64") return SF_FORMAT_W64 | SF_FORMAT_DOUBLE;
  if (extension == ".rf64") return SF_FORMAT_RF64 | SF_FORMAT_DOUBLE;
  if (extension == ".aif" || extension == ".aiff" || extension == ".aifc") {
    return SF_FORMAT_AIFF | SF_FORMAT_DOUBLE;
  }
  if (extension == ".caf") return SF_FORMAT_CAF | SF_FORMAT_DOUBLE;
  if (extension == ".flac") return SF_FORMAT_FLAC | SF_FORMAT_PCM_24;
  return 0;
}

bool stores_24_bit_integers(int format) { return (format & SF_FORMAT_SUBMASK) == SF_FORMAT_PCM_24; }

void write_sound(const std::vector<double>& stored, const Sidecar& sidecar, int format,
                 const std::string& file_path, const std::string& path) {
  const auto channels = static_cast<int>(sidecar.channels.size());
  const double rate_hz = std::round(sidecar.sample_rate_hz);
  if (!(rate_hz >= 1.0 && rate_hz <= std::numeric_limits<int>::max())) {
    throw InputError(path + ": a sound container cannot store the sample rate " +
                     number_text(sidecar.sample_rate_hz) + " Hz");
  }
  SF_INFO info{};
  info.samplerate = static_cast<int>(rate_hz);
  info.channels = channels;
  info.format = format;
  if (sf_format_check(&info) == SF_FALSE) {
    throw InputError(path + ": " + sound_container_name(format) + " cannot store " +
                     std::to_string(channels) + " channels at " + number_text(rate_hz) + " Hz");
  }
  SndfileHandle file(sf_open(file_path.c_str(), SFM_WRITE, &info));
  if (!file) throw InputError(path + ": cannot write: " + sf_strerror(nullptr));
  sf_command(file.get(), SFC_SET_NORM_DOUBLE, nullptr, SF_FALSE);  // integers are counts
  const auto frames = static_cast<sf_count_t>(stored.size() / channels);
  if (sf_writef_double(file.get(), stored.data(), frames) != frames) {
    throw InputError(path + ": cannot write: " + sf_strerror(file.get()));
  }
  const int closed = sf_close(file.release());
  if (closed != 0) throw InputError(path + ": cannot write: " + sf_error_number(closed));
}

}  // namespace oscilab::daq

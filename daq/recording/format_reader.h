#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "daq/recording/opening_control.h"
#include "daq/recording/recording.h"

namespace oscilab::daq {

/// One signal a file holds, as its format names it and as a sidecar's "source" names it.
struct FileSignal {
  std::string name;                      // e.g. "analog/NI_9775/ai0", "V1", "/data_product/data"
  std::int64_t sample_count = 0;         // samples per column
  std::int64_t columns = 1;              // > 1: a matrix whose columns a sidecar picks by "column"
  std::string unit;                      // as the file states it; "" when it states none
  std::optional<double> sample_rate_hz;  // when the file states it (an increment, an attribute)
  std::string stored_type;               // how the values are stored: "float64", "int16", ...
  nlohmann::json properties = nlohmann::json::object();  // what else the file says of it
};

/// What a file holds (`oscilab-cli info`): enough to write the sidecar that maps it.
struct FileContents {
  std::string container;  // "NI TDMS 2.0, 4 segments", "UFF 58b, little-endian", ...
  std::vector<FileSignal> file_signals;
  nlohmann::json properties = nlohmann::json::object();  // the file's own properties
  /// Whether a sidecar picks signals by channels[].source (files of named signals); false for
  /// sound files (channels in order) and CSV (columns by the channel's name or "column").
  bool picked_by_source = true;
};

/// One file format. Each lives in its own file under daq/recording/formats/; read_recording
/// chooses one by the file's first bytes, then by its extension (formats_for_file).
class FormatReader {
 public:
  virtual ~FormatReader() = default;
  /// "NI TDMS", "UFF 58", ...
  virtual std::string_view format_name() const = 0;
  /// Whether `head` (the file's first bytes, at most 512) is this format's signature.
  virtual bool matches_signature(std::string_view head) const = 0;
  /// Whether the lower-case extension with its dot (".tdms") is this format's.
  virtual bool matches_extension(std::string_view extension) const = 0;
  /// What the file holds, without reading its samples where the format allows it. Throws
  /// InputError naming the file and the problem.
  virtual FileContents describe(const std::string& path) const = 0;
  /// Reads the samples the sidecar maps into a recording (calibrated to SI; `samples_stored` as
  /// the file stores them after the format's own scaling). `sidecar_name` names the sidecar in
  /// messages. Throws InputError naming the file and the problem.
  virtual Recording read(const std::string& path, const Sidecar& sidecar,
                         const std::string& sidecar_name) const = 0;
  /// read() with `control`: its progress as the share of the read done, its token polled as it
  /// goes (throws OpeningCancelled). A format read in one piece (this default) polls before and
  /// after, and reports 1 at the end.
  virtual Recording read_controlled(const std::string& path, const Sidecar& sidecar,
                                    const std::string& sidecar_name,
                                    const OpeningControl& control) const;
};

/// A format whose files hold named signals (TDMS, MATLAB, HDF5, UFF 58): it only lists and reads
/// signals; mapping them onto the sidecar's channels is shared (read_mapped_signals).
class SignalFileReader : public FormatReader {
 public:
  /// The values of one signal (one column of a matrix: `column` ≥ 0), in file order, after the
  /// format's own scaling (e.g. DAQmx linear scales) and nothing else. Throws InputError.
  virtual std::vector<double> read_signal(const std::string& path, const FileSignal& signal,
                                          int column) const = 0;
  Recording read(const std::string& path, const Sidecar& sidecar,
                 const std::string& sidecar_name) const override;
  /// Reports the share of the mapped signals read, polls the token between signals.
  Recording read_controlled(const std::string& path, const Sidecar& sidecar,
                            const std::string& sidecar_name,
                            const OpeningControl& control) const override;
};

/// Every format Oscilab reads, most specific signature first.
const std::vector<const FormatReader*>& known_formats();
/// The format of `path`: the first whose signature matches the file's first bytes, else the
/// first whose extension matches. Throws InputError naming the file when none does.
const FormatReader& format_for_file(const std::string& path);

}  // namespace oscilab::daq

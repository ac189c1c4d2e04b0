// MATLAB MAT-files (Level 4, Level 5 "v5/v6/v7", and v7.3, which is HDF5): the reader the
// program sees. Its matio calls live in oscilab_hdf5_module (matio_library.cpp, and
// hdf5_library.cpp for v7.3 files), which it loads on its first file, and run in a child process
// (library_process.h).
#include <cstring>
#include <filesystem>
#include <fstream>

#include "analysis/common/input_error.h"
#include "daq/hdf5_module/hdf5_module_loader.h"
#include "daq/recording/file_bytes.h"
#include "daq/recording/formats/contents_text.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/formats/hdf5_format.h"
#include "daq/recording/formats/library_process.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

constexpr const char* kMatioLibrary = "matio";

// Whether the file starts with MATLAB's v7.3 header (its HDF5 part is then read by libhdf5).
bool is_mat73(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(19, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  return in.gcount() == 19 && head == "MATLAB 7.3 MAT-file";
}

class MatFormat final : public SignalFileReader {
 public:
  std::string_view format_name() const override { return "MATLAB MAT-file"; }
  bool matches_signature(std::string_view head) const override {
    return head.starts_with("MATLAB 5.0 MAT-file") || head.starts_with("MATLAB 7.3 MAT-file");
  }
  bool matches_extension(std::string_view extension) const override { return extension == ".mat"; }

  FileContents describe(const std::string& path) const override {
    check_data_file(path);
    if (is_mat73(path)) return describe_mat73(path);
    // A variable's description takes well under 64 bytes of the file per 1 KiB of text.
    const std::size_t reply = (std::size_t{1} << 20) + 64 * file_bytes(path);
    const OscilabHdf5ModuleV1& module = hdf5_module("reading " + path);
    const std::string text = run_in_child(path, kMatioLibrary, child_limits_for(path, reply), [&] {
      return child_reply(module.describe_mat(path.c_str()));
    });
    return contents_from_text(text, path);
  }

  std::vector<double> read_signal(const std::string& path, const FileSignal& signal,
                                  int column) const override {
    if (is_mat73(path)) return read_mat73_signal(path, signal, column);
    const std::size_t reply = static_cast<std::size_t>(signal.sample_count) * sizeof(double);
    const OscilabHdf5ModuleV1& module = hdf5_module("reading " + path);
    const std::string bytes = run_in_child(path, kMatioLibrary, child_limits_for(path, reply), [&] {
      return child_reply(module.read_mat(path.c_str(), signal.name.c_str(), signal.sample_count,
                                         signal.columns, column));
    });
    if (bytes.size() != reply) {
      throw InputError(path + ": variable " + in_quotes(signal.name) + ": read " +
                       std::to_string(bytes.size() / sizeof(double)) + " values, expected " +
                       std::to_string(signal.sample_count));
    }
    std::vector<double> values(static_cast<std::size_t>(signal.sample_count));
    std::memcpy(values.data(), bytes.data(), bytes.size());
    return values;
  }
};

}  // namespace

const FormatReader& mat_format() {
  static const MatFormat format;
  return format;
}

}  // namespace oscilab::daq

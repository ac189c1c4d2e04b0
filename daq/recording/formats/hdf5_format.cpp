// HDF5 files through libhdf5, whose calls live in oscilab_hdf5_module (hdf5_library.cpp) and run
// in a child process (library_process.h): this is the reader the program sees, which loads the
// module on its first file. Every numeric 1-D or 2-D dataset is a signal named by its path; the
// rate and the unit come from attributes. See "HDF5 File Format Specification Version 3.0" (The
// HDF Group) for the signature and the user block.
#include <cstring>
#include <filesystem>
#include <functional>

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

constexpr const char* kHdf5Library = "libhdf5";
constexpr std::string_view kSignature = "\x89HDF\r\n\x1a\n";

// A libhdf5 call of the module in a child process, with the module loaded in this one first.
std::string run_hdf5(const std::string& path, std::size_t reply,
                     const std::function<ChildReply(const OscilabHdf5ModuleV1&)>& work) {
  const OscilabHdf5ModuleV1& module = hdf5_module("reading " + path);
  return run_in_child(path, kHdf5Library, child_limits_for(path, reply),
                      [&] { return work(module); });
}

class Hdf5Format final : public SignalFileReader {
 public:
  std::string_view format_name() const override { return "HDF5"; }
  bool matches_signature(std::string_view head) const override {
    return head.starts_with(kSignature);
  }
  bool matches_extension(std::string_view extension) const override {
    return extension == ".h5" || extension == ".hdf5" || extension == ".he5";
  }

  FileContents describe(const std::string& path) const override {
    check_data_file(path);
    const std::size_t reply = (std::size_t{1} << 20) + 64 * file_bytes(path);
    const std::string text = run_hdf5(path, reply, [&](const OscilabHdf5ModuleV1& module) {
      return child_reply(module.describe_hdf5(path.c_str(), 0));
    });
    return contents_from_text(text, path);
  }

  std::vector<double> read_signal(const std::string& path, const FileSignal& signal,
                                  int column) const override {
    const std::size_t reply = static_cast<std::size_t>(signal.sample_count) * sizeof(double);
    const std::string bytes = run_hdf5(path, reply, [&](const OscilabHdf5ModuleV1& module) {
      return child_reply(
          module.read_hdf5(path.c_str(), signal.name.c_str(), signal.sample_count, column, 0));
    });
    if (bytes.size() != reply) {
      throw InputError(path + ": dataset " + signal.name + ": read " +
                       std::to_string(bytes.size() / sizeof(double)) + " values, expected " +
                       std::to_string(signal.sample_count));
    }
    std::vector<double> values(static_cast<std::size_t>(signal.sample_count));
    std::memcpy(values.data(), bytes.data(), bytes.size());
    return values;
  }
};

}  // namespace

FileContents describe_mat73(const std::string& path) {
  const std::size_t reply = (std::size_t{1} << 20) + 64 * file_bytes(path);
  const std::string text = run_hdf5(path, reply, [&](const OscilabHdf5ModuleV1& module) {
    return child_reply(module.describe_hdf5(path.c_str(), 1));
  });
  return contents_from_text(text, path);
}

std::vector<double> read_mat73_signal(const std::string& path, const FileSignal& signal,
                                      int column) {
  const std::size_t reply = static_cast<std::size_t>(signal.sample_count) * sizeof(double);
  const std::string bytes = run_hdf5(path, reply, [&](const OscilabHdf5ModuleV1& module) {
    return child_reply(
        module.read_hdf5(path.c_str(), signal.name.c_str(), signal.sample_count, column, 1));
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

const FormatReader& hdf5_format() {
  static const Hdf5Format format;
  return format;
}

}  // namespace oscilab::daq

// oscilab_hdf5_module's entry point (hdf5_module_api.h): the C functions around the readers' and
// the writer's C++ code, each catching whatever that code throws (std::bad_alloc), so that no
// exception leaves the module.
#include <cstdlib>
#include <cstring>
#include <string>

#include "daq/export/mat_file_writer.h"
#include "daq/hdf5_module/hdf5_module_api.h"
#include "daq/recording/formats/hdf5_library.h"
#include "daq/recording/formats/matio_library.h"

namespace oscilab::daq {
namespace {

// A C++ reply copied into memory from malloc, which the caller frees.
OscilabModuleReplyV1 c_reply(const ChildReply& reply) {
  char* bytes = nullptr;
  if (!reply.bytes.empty()) {
    bytes = static_cast<char*>(std::malloc(reply.bytes.size()));
    if (bytes == nullptr) return {0, nullptr, 0};
    std::memcpy(bytes, reply.bytes.data(), reply.bytes.size());
  }
  return {reply.ok ? 1 : 0, bytes, reply.bytes.size()};
}

template <typename Work>
OscilabModuleReplyV1 replying(const Work& work) noexcept {
  try {
    return c_reply(work());
  } catch (...) {
    return {0, nullptr, 0};  // out of memory: the caller says so
  }
}

void initialise() noexcept { initialise_hdf5(); }

OscilabModuleReplyV1 describe_hdf5(const char* path, int mat73) noexcept {
  return replying([&] { return describe_hdf5_file(path, mat73 != 0); });
}

OscilabModuleReplyV1 read_hdf5(const char* path, const char* name, int64_t sample_count, int column,
                               int mat73) noexcept {
  return replying([&] { return read_hdf5_values(path, name, sample_count, column, mat73 != 0); });
}

OscilabModuleReplyV1 describe_mat(const char* path) noexcept {
  return replying([&] { return describe_mat_file(path); });
}

OscilabModuleReplyV1 read_mat(const char* path, const char* name, int64_t sample_count,
                              int64_t columns, int column) noexcept {
  return replying([&] { return read_mat_values(path, name, sample_count, columns, column); });
}

OscilabMatWriteResultV1 write_mat(const char* path, const OscilabMatVariableV1* variables,
                                  size_t count) noexcept {
  try {
    return write_mat_file(path, variables, count);
  } catch (...) {
    return {kOscilabMatUnexpected, 0, 0};
  }
}

constexpr OscilabHdf5ModuleV1 kFunctions = {initialise,   describe_hdf5, read_hdf5,
                                            describe_mat, read_mat,      write_mat};

}  // namespace
}  // namespace oscilab::daq

extern "C" __attribute__((visibility("default"))) const OscilabHdf5ModuleV1*
oscilab_hdf5_module_v1() {
  return &oscilab::daq::kFunctions;
}

#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <system_error>

namespace oscilab::daq {

/// The size of the file at `path` in bytes, 0 when it cannot be read: the readers' bound on what
/// a file may declare (values, strings, chunks) before anything is allocated for it.
inline std::size_t file_bytes(const std::string& path) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  return error ? 0 : static_cast<std::size_t>(size);
}

}  // namespace oscilab::daq

#include "daq/recording/json_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::daq {

nlohmann::json read_json_file(const std::string& path, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(path + ": file not found");
  if (!fs::is_regular_file(status)) throw InputError(path + ": not a regular file");
  const std::uintmax_t size = fs::file_size(path, error);
  if (!error && size > max_bytes) {
    throw InputError(path + ": " + std::to_string(size) + " bytes is too large for this file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path + ": cannot read: " + std::strerror(errno));
  return parse_json_within_limits(text, path);
}

void write_text_file_atomically(const std::string& text, const std::string& path) {
  TemporaryFile file(path);
  {
    std::ofstream out(file.path(), std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot write: " + std::strerror(errno));
    out << text;
    out.flush();
    if (!out) throw InputError(path + ": cannot write: " + std::strerror(errno));
  }
  // On the disk before the rename: a power cut then leaves the old file or the new one whole,
  // never a renamed file whose bytes were not written yet (an empty sidecar, a lost recording).
  const int fd = ::open(file.path().c_str(), O_RDONLY | O_CLOEXEC);
  const int error = fd < 0 || ::fdatasync(fd) != 0 ? errno : 0;
  if (fd >= 0) ::close(fd);
  if (error != 0) throw InputError(path + ": cannot write: " + std::strerror(error));
  file.commit();
}

}  // namespace oscilab::daq

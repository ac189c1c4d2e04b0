#include "daq/recording/temporary_file.h"

#include <atomic>
#include <filesystem>
#include <system_error>
#include <utility>

#include <unistd.h>

#include "analysis/common/input_error.h"

namespace oscilab::daq {

namespace fs = std::filesystem;

TemporaryFile::TemporaryFile(std::string target) : target_(std::move(target)) {
  static std::atomic<unsigned> counter{0};
  path_ =
      target_ + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
}

TemporaryFile::~TemporaryFile() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove(path_, ignored);
}

void TemporaryFile::commit() {
  std::error_code error;
  fs::rename(path_, target_, error);
  if (error) throw InputError(target_ + ": cannot write: " + error.message());
  committed_ = true;
}

}  // namespace oscilab::daq

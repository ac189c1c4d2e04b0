#pragma once

#include <string>

namespace oscilab::daq {

/// A file written under a temporary name beside its target and renamed into place by commit(),
/// so that a failed write leaves neither a half-written target nor the temporary behind (the
/// destructor removes an uncommitted temporary). Not thread-safe; one writer per instance.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::string target);
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile();

  /// Where to write: `target.tmp.PID.N`, in the target's directory (same file system, so the
  /// rename is atomic).
  const std::string& path() const { return path_; }
  const std::string& target() const { return target_; }

  /// Renames the temporary onto the target; throws InputError naming the target on failure.
  void commit();

 private:
  std::string target_;
  std::string path_;
  bool committed_ = false;
};

}  // namespace oscilab::daq

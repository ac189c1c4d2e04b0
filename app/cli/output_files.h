#pragma once
// What a command writes, never over what it reads, and all or nothing.

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/sidecar.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::cli {

/// Whether two paths name one file: the same file when both exist (links and hard links
/// included), else the same canonical path.
inline bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(a, error) && fs::exists(b, error)) {
    const bool same = fs::equivalent(a, b, error);
    if (!error) return same;
  }
  const fs::path canonical_a = fs::weakly_canonical(a, error);
  if (error) return false;
  const fs::path canonical_b = fs::weakly_canonical(b, error);
  return !error && canonical_a == canonical_b;
}

/// Throws InputError naming `option` when `output` is one of `inputs`.
inline void refuse_output_over_inputs(const std::string& output, const std::string& option,
                                      const std::vector<std::string>& inputs) {
  if (output.empty()) return;
  for (const std::string& input : inputs) {
    if (same_file(output, input)) {
      throw InputError(option + ": " + output + " is an input of this command (" + input +
                       "); write elsewhere");
    }
  }
}

/// The recordings given and the sidecars beside them: what an output must not overwrite.
inline std::vector<std::string> recordings_and_sidecars(const std::vector<std::string>& records) {
  std::vector<std::string> inputs = records;
  for (const std::string& record : records) inputs.push_back(daq::sidecar_path_for(record));
  return inputs;
}

/// The files a command writes, each under a temporary name beside its target (TemporaryFile),
/// renamed into place together by commit() once every one is complete. A run that fails before
/// (a full disk, a refused option) leaves none of them and none of the temporaries.
class OutputFiles {
 public:
  /// Where to write `target` now.
  const std::string& add(const std::string& target) {
    files_.push_back(std::make_unique<daq::TemporaryFile>(target));
    return files_.back()->path();
  }
  /// Writes `target`'s temporary with `fill(std::ostream&)` and closes it; throws InputError
  /// naming `target` when the file cannot be opened or a byte of it did not reach the disk.
  template <class Fill>
  void write(const std::string& target, Fill&& fill) {
    std::ofstream out(add(target), std::ios::binary);
    if (!out) throw InputError(target + ": cannot write: " + std::strerror(errno));
    fill(out);
    out.close();  // the last buffer is written here: a full disk shows only now
    if (!out) throw InputError(target + ": write failed: " + std::strerror(errno));
  }
  /// Writes `target`'s temporary with `write_to_path(path)`, for writers that take a file name (a
  /// PNG figure); an InputError they throw names `target`, not the temporary.
  template <class WriteToPath>
  void write_to(const std::string& target, WriteToPath&& write_to_path) {
    const std::string path = add(target);
    try {
      write_to_path(path);
    } catch (const InputError& error) {
      std::string message = error.what();
      for (auto at = message.find(path); at != std::string::npos;
           at = message.find(path, at + target.size())) {
        message.replace(at, path.size(), target);
      }
      throw InputError(message);
    }
  }
  /// Renames every temporary onto its target, in the order added.
  void commit() {
    for (const auto& file : files_) file->commit();
  }

 private:
  std::vector<std::unique_ptr<daq::TemporaryFile>> files_;
};

/// One file written with `fill(std::ostream&)` under a temporary name and renamed into place when
/// complete (OutputFiles::write, then commit).
template <class Fill>
void write_output_file(const std::string& target, Fill&& fill) {
  OutputFiles output;
  output.write(target, std::forward<Fill>(fill));
  output.commit();
}

}  // namespace oscilab::cli

#pragma once

#include <string>

#include "analysis/common/job.h"

namespace oscilab::cli {

/// A progress bar on stderr for long work, drawn only when stderr is a terminal (contract §2);
/// otherwise silent, so logs and pipes stay clean.
class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();  // ends the line
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// A ProgressFn that draws this bar; valid while the bar lives.
  ProgressFn callback();

 private:
  void draw(double fraction);

  std::string label_;
  bool enabled_;
  int last_percent_ = -1;
};

}  // namespace oscilab::cli

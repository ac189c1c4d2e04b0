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
  /// Draws the bar with what the work is doing after it ("step 1 of at most 3: …"); redrawn
  /// when the percentage or the text changes.
  void show(double fraction, const std::string& detail);

 private:
  void draw(double fraction) { show(fraction, detail_); }

  std::string label_;
  bool enabled_;
  int last_percent_ = -1;
  std::string detail_;
};

}  // namespace oscilab::cli

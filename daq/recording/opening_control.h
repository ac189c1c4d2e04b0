#pragma once

#include <exception>

#include "analysis/common/job.h"

namespace oscilab::daq {

/// Thrown by an opening (or a read) whose token was cancelled: nothing was opened.
class OpeningCancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "opening cancelled"; }
};

/// How far an opening has gone and whether to stop it. `progress` gets a fraction in [0, 1]
/// (from the opening's thread); `cancel` is polled as the opening goes, which then throws
/// OpeningCancelled.
struct OpeningControl {
  ProgressFn progress;
  CancelToken cancel;
};

}  // namespace oscilab::daq

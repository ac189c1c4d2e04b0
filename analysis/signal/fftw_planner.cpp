#include "analysis/signal/fftw_planner.h"

namespace oscilab::analysis {

std::mutex& fftw_planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace oscilab::analysis

#pragma once

#include <mutex>

#include <fftw3.h>

namespace oscilab::analysis {

/// FFTW's planner (plan creation and destruction) is not thread-safe; its execute functions are.
/// Every place that makes or destroys a plan holds this one lock (FFTW manual, "Thread safety").
std::mutex& fftw_planner_mutex();

/// Real-to-complex and complex-to-real plans of size n, made once (FFTW_ESTIMATE |
/// FFTW_UNALIGNED) and kept for the life of the process. Making a plan computes its twiddle
/// factors, which for a long record costs several times the transform itself; a cached plan is
/// run on any arrays with fftw_execute_dft_r2c / fftw_execute_dft_c2r (thread-safe).
fftw_plan cached_r2c_plan(int n);
fftw_plan cached_c2r_plan(int n);

}  // namespace oscilab::analysis

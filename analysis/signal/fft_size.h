#pragma once

#include <cstddef>

namespace oscilab::analysis {

/// The smallest n' ≥ n whose only prime factors are 2, 3, 5 and 7: FFTW's fast sizes. A record of
/// prime length (134401 samples is prime) otherwise costs several times more.
std::size_t fast_fft_size(std::size_t n);

}  // namespace oscilab::analysis

#include "analysis/signal/fft_size.h"

#include <initializer_list>

namespace oscilab::analysis {

std::size_t fast_fft_size(std::size_t n) {
  if (n <= 1) return 1;
  for (std::size_t candidate = n;; ++candidate) {
    std::size_t m = candidate;
    for (std::size_t p : {2u, 3u, 5u}) {
      while (m % p == 0) m /= p;
    }
    if (m == 1) return candidate;
  }
}

}  // namespace oscilab::analysis

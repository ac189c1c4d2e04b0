#pragma once

#include <cmath>
#include <optional>

namespace oscilab::analysis {

/// Refines a sign change of g on [a, b] (g(a) = g_a and g(b) = g_b of opposite signs) by the
/// Illinois variant of regula falsi (Dowell & Jarratt 1971): superlinear, and always bracketed.
/// `g(c)` evaluates g at the secant's point c, or returns nothing when it cannot (a corrector
/// that failed there), which ends the search; the caller keeps what its last evaluation found.
/// Ends at a zero, once the bracket is no wider than `tolerance`, or after `max_evaluations`.
template <typename Evaluate>
void illinois_regula_falsi(double a, double g_a, double b, double g_b, double tolerance,
                           Evaluate&& g, int max_evaluations = 60) {
  for (int evaluation = 0; evaluation < max_evaluations && std::abs(b - a) > tolerance;
       ++evaluation) {
    const double c = (a * g_b - b * g_a) / (g_b - g_a);
    const std::optional<double> g_c = g(c);
    if (!g_c || *g_c == 0.0) return;
    if ((*g_c > 0.0) != (g_b > 0.0)) {
      a = b;  // the sign change is now between b and c
      g_a = g_b;
    } else {
      g_a *= 0.5;  // the Illinois step: halve the retained end's value
    }
    b = c;
    g_b = *g_c;
  }
}

}  // namespace oscilab::analysis

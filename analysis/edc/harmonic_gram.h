#pragma once

#include <Eigen/Core>

namespace oscilab::analysis {

/// The Gram matrix AᵀA of the cycle fit's basis (cycle_fit.h) over n evenly spaced samples, in
/// closed form: O(H²) work instead of the O(n H²) of summing the rows' products.
///
/// The basis columns at sample j are 1, τ_j, cos hθ_j, −sin hθ_j (h = 1..H), with
///   θ_j = θ_0 + j Δθ  and  τ_j = τ_0 + j Δt,  j = 0..n−1.
/// Every product of two columns is, by the product-to-sum identities, a sum over the samples of
/// cos kθ or sin kθ (k = 0..2H), possibly times τ, and about the middle sample those sums are
/// Dirichlet kernels: with c = (n−1)/2 and u = j − c,
///   Σ_j e^{ikθ_j} = e^{ikθ_c} D(kΔθ),         D(x) = Σ_u e^{iux} = sin(nx/2) / sin(x/2),
///   Σ_j u e^{ikθ_j} = i e^{ikθ_c} G(kΔθ),      G(x) = Σ_u u sin(ux) = −D'(x),
/// and Σ_j u² = n (n² − 1)/12.
///
/// D and G divide by sin(x/2). For x/2 below π/2 that is harmless (a small x is itself
/// accurate, and over a window of about one period n x is not small), but where x/2 nears mπ,
/// m ≥ 1 (an order up to 2H at a multiple of the sample rate), the sine's relative error grows
/// as ε (x/2) / |sin(x/2)|. Returns false, with `gram` undefined, when there some
/// |sin(kΔθ/2)| is below kMinHalfAngleSine: then the rows' products must be summed. Otherwise
/// the entries' rounding error stays below about n ε · 2H / kMinHalfAngleSine (a few 1e-12 of
/// the largest entry, n), far below what the least squares resolve.
///
/// Fills the whole symmetric matrix, (2 + 2H) × (2 + 2H).
inline constexpr double kMinHalfAngleSine = 0.03;
bool harmonic_gram_evenly_spaced(int n, double theta0_rad, double dtheta_rad, double tau0_s,
                                 double dt_s, int harmonics, Eigen::MatrixXd& gram);

}  // namespace oscilab::analysis

#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace oscilab::analysis {

/// How a term enters the energy balance: an elastic force has a potential U(z) (energy stored and
/// returned), a dissipative force turns work into heat (∮ D dz > 0 over a cycle).
enum class TermKind { Elastic, Dissipative };

/// Partial derivatives of a term's force F(z, ż) at one point; used by implicit solvers, harmonic
/// balance (analytic Jacobian) and the variational equation for stability.
struct TermPartials {
  double d_dz = 0.0;      // ∂F/∂z
  double d_dz_dot = 0.0;  // ∂F/∂ż
};

/// Sensitivities of one step s₁ = advance(s₀; z₀ → z₁) of a one-value, rate-independent state:
/// what a periodic-state solver needs for an exact periodic state and an analytic Jacobian.
struct StateStepSensitivity {
  double d_state = 1.0;  // ∂s₁/∂s₀
  double d_z0 = 0.0;     // ∂s₁/∂z₀
  double d_z1 = 0.0;     // ∂s₁/∂z₁
  double log_d_state = 0.0;  // ln ∂s₁/∂s₀ when ∂s₁/∂s₀ > 0 (products of many steps in logs)
  bool affine = false;  // s₁ is affine in s₀ (a shift of s₀ shifts s₁ by ∂s₁/∂s₀ times it)
};

/// Where the cubic Hermite path from (z0, ż0) to (z1, ż1) over dt turns (ż = 0 inside the step),
/// the path every solver that samples a known orbit assumes between samples
/// (ModelTerm::advance_state). A rate-independent state reverses at the turning point's z, not at
/// the nearer sample: stepping through it makes the state a continuous function of the orbit.
struct HermiteTurn {
  bool inside = false;  // ż0 and ż1 have opposite signs: one turning point in (0, 1)
  double theta = 0.0;   // its place in the step, θ ∈ (0, 1)
  double z_m = 0.0;     // z at it
  /// ∂z_turn/∂z0, ∂z_turn/∂z1, ∂z_turn/∂ż0, ∂z_turn/∂ż1 at fixed θ (the path is stationary in θ
  /// there, so these are the whole derivatives): the Hermite weights h00, h01, h10 dt, h11 dt.
  double d_z0 = 0.0, d_z1 = 0.0, d_v0 = 0.0, d_v1 = 0.0;
};
HermiteTurn hermite_turning_point(double z0_m, double z_dot0_m_s, double z1_m, double z_dot1_m_s,
                                  double dt_s);

/// The Dahl state's exact step along a monotone stretch z0 → z1 (Dahl 1968): with d = sgn Δz and
/// a = e^(−κ|Δz|), s₁ = d + (s₀ − d) a; ∂s₁/∂s₀ = a, ∂s₁/∂z₁ = −∂s₁/∂z₀ = κ a (1 − d s₀) (at Δz = 0
/// the mean of both sides, κ). κ in 1/m: σ0/F_c of the Dahl element, 1/δ of a friction's
/// presliding regime.
void dahl_step(double kappa_1_m, double z0_m, double z1_m, double* state,
               StateStepSensitivity& out);

/// One named contribution to the restoring surface R(z, ż) of eq. (1): m z̈ + Σ F_i(z, ż, s_i) = f.
///
/// A term may carry an internal state s (for hysteresis: Dahl, Maxwell slip) whose rate is
/// ds/dt = state_rate(z, ż, s); stateless terms keep the defaults. Terms compose: a model is a
/// mass and a list of terms, and every solver (time integration, harmonic balance) reaches the
/// physics only through this interface.
///
/// Thread-safety: all const methods are safe to call concurrently.
class ModelTerm {
 public:
  virtual ~ModelTerm() = default;

  /// JSON `type` of the term, e.g. "polynomial-stiffness".
  virtual std::string type() const = 0;
  virtual TermKind kind() const = 0;

  /// Force of the term on the left-hand side of eq. (1), in N. `state` points at state_size()
  /// values. **Force without a state**: with `state` nullptr a stateful term gives the part of
  /// its force that does not depend on the state (0 for a pure hysteresis element such as the
  /// Dahl element); solvers that track the state on a sampled orbit (HysteresisMarch) add the
  /// rest, force(z, ż, s) − force(z, ż, nullptr), which must not depend on ż explicitly. The same
  /// split holds for partials().
  virtual double force(double z_m, double z_dot_m_s, const double* state) const = 0;
  virtual TermPartials partials(double z_m, double z_dot_m_s, const double* state) const = 0;

  /// Internal state: size, value at rest at position z, and rate ds/dt.
  virtual int state_size() const { return 0; }
  virtual void initial_state(double /*z_m*/, double* /*state*/) const {}
  virtual void state_rate(double /*z_m*/, double /*z_dot_m_s*/, const double* /*state*/,
                          double* /*rate*/) const {}
  /// Advances the state along the motion from (z0, ż0) to (z1, ż1), taken as a cubic Hermite
  /// path over dt seconds: what a solver that samples a known orbit (harmonic balance) needs.
  /// The default integrates state_rate with classical RK4 in 8 sub-steps; terms with an exact
  /// update (a rate-independent hysteresis) override it.
  virtual void advance_state(double z0_m, double z_dot0_m_s, double z1_m, double z_dot1_m_s,
                             double dt_s, double* state) const;
  /// The state's update along a monotone stretch from z0 to z1 with its sensitivities, for a
  /// term whose state is one value updated by the path of z alone (rate-independent
  /// hysteresis). Returns false when the term offers none; solvers then fall back to marching
  /// period after period and finite differences. Such a term's advance_state() is
  /// advance_rate_independent(): this update, through the path's turning point when the step
  /// holds one.
  virtual bool advance_state_sensitivity(double /*z0_m*/, double /*z1_m*/, double* /*state*/,
                                         StateStepSensitivity& /*out*/) const {
    return false;
  }
  /// ∂F/∂s of a one-value state at (z, ż, s); 0 for stateless terms.
  virtual double force_d_state(double /*z_m*/, double /*z_dot_m_s*/,
                               const double* /*state*/) const {
    return 0.0;
  }

  /// Potential energy U(z) in J of an elastic term (U' = F at rest); 0 for dissipative terms.
  virtual double potential_j(double /*z_m*/) const { return 0.0; }

  /// Named parameters (SI, names carry units as in the JSON keys), for fits and sensitivity.
  virtual std::vector<std::string> parameter_names() const = 0;
  virtual double parameter(const std::string& name) const = 0;
  /// Throws InputError for an unknown name or a value outside the term's domain.
  virtual void set_parameter(const std::string& name, double value) = 0;

  /// {"type": type(), <parameters>}; term_from_json() reads it back.
  virtual nlohmann::json to_json() const = 0;
  virtual std::unique_ptr<ModelTerm> clone() const = 0;

 protected:
  /// advance_state() of a rate-independent term: advance_state_sensitivity() from z0 to z1, in
  /// two monotone stretches through the Hermite path's turning point when the step holds one.
  void advance_rate_independent(double z0_m, double z_dot0_m_s, double z1_m, double z_dot1_m_s,
                                double dt_s, double* state) const;
};

}  // namespace oscilab::analysis

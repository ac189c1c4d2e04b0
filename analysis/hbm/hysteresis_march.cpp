#include "analysis/hbm/hysteresis_march.h"

#include <algorithm>
#include <cmath>

namespace oscilab::analysis {
namespace {

// The part of a stateful term's force that its state carries (ModelTerm, "force without a state").
double state_part(const ModelTerm& term, double z_m, double z_dot_m_s, const double* state) {
  return term.force(z_m, z_dot_m_s, state) - term.force(z_m, z_dot_m_s, nullptr);
}

// One step of a term's state from sample k to k + 1 along the Hermite path between them, through
// its turning point when the step holds one (hermite_turning_point): the combined sensitivities
// ∂s₁/∂s₀ (a, and its log), ∂s₁/∂z_k, ∂s₁/∂z_{k+1}, ∂s₁/∂ż_k, ∂s₁/∂ż_{k+1} (the last two through
// the turning point's z only).
struct MarchStep {
  double a = 1.0, log_a = 0.0;
  double dz0 = 0.0, dz1 = 0.0, dv0 = 0.0, dv1 = 0.0;
  bool affine = true;
};

MarchStep march_step(const ModelTerm& term, double z0, double v0, double z1, double v1, double dt,
                     double& s) {
  MarchStep out;
  const HermiteTurn turn = hermite_turning_point(z0, v0, z1, v1, dt);
  StateStepSensitivity first;
  if (!turn.inside) {
    term.advance_state_sensitivity(z0, z1, &s, first);
    out.a = first.d_state;
    out.log_a = first.log_d_state;
    out.dz0 = first.d_z0;
    out.dz1 = first.d_z1;
    out.affine = first.affine;
    return out;
  }
  StateStepSensitivity second;
  term.advance_state_sensitivity(z0, turn.z_m, &s, first);
  term.advance_state_sensitivity(turn.z_m, z1, &s, second);
  // s₁ = g₂(g₁(s₀, z0, z*), z*, z1): the chain rule, z* moving with the orbit's samples.
  const double d_turn = second.d_state * first.d_z1 + second.d_z0;
  out.a = first.d_state * second.d_state;
  out.log_a = first.log_d_state + second.log_d_state;
  out.dz0 = second.d_state * first.d_z0 + d_turn * turn.d_z0;
  out.dz1 = second.d_z1 + d_turn * turn.d_z1;
  out.dv0 = d_turn * turn.d_v0;
  out.dv1 = d_turn * turn.d_v1;
  out.affine = first.affine && second.affine;
  return out;
}

}  // namespace

double small_loop_stiffness_n_m(const Model& model, double z_m) {
  double stiffness = 0.0;
  for (const auto& term : model.terms()) {
    if (term->state_size() != 1) continue;
    double state = 0.0;
    term->initial_state(z_m, &state);
    double advanced = state;
    StateStepSensitivity at_rest;
    if (term->advance_state_sensitivity(z_m, z_m, &advanced, at_rest)) {
      stiffness += term->force_d_state(z_m, 0.0, &state) * at_rest.d_z1;
    }
  }
  return stiffness;
}

HysteresisMarch::HysteresisMarch(const Model& model, double tolerance, int max_periods)
    : tolerance_(tolerance), max_periods_(max_periods) {
  exact_ = true;
  for (std::size_t i = 0; i < model.terms().size(); ++i) {
    const ModelTerm& term = *model.terms()[i];
    if (term.state_size() == 0) continue;
    terms_.push_back(i);
    double probe = 0.0;
    StateStepSensitivity unused;
    if (term.state_size() != 1 || !term.advance_state_sensitivity(0.0, 1e-9, &probe, unused)) {
      exact_ = false;
    }
  }
  if (terms_.empty()) exact_ = false;
  state_.assign(static_cast<std::size_t>(model.state_size()), 0.0);
  start_of_period_ = state_;
}

int HysteresisMarch::forces(const Model& model, const Eigen::VectorXd& z_m,
                            const Eigen::VectorXd& z_dot_m_s, double period_s,
                            Eigen::VectorXd& force_n) {
  force_n.setZero(z_m.size());
  if (!active() || z_m.size() == 0) return 0;
  return exact_ ? exact_forces(model, z_m, z_dot_m_s, period_s, force_n)
                : marched_forces(model, z_m, z_dot_m_s, period_s, force_n);
}

int HysteresisMarch::exact_forces(const Model& model, const Eigen::VectorXd& z_m,
                                  const Eigen::VectorXd& z_dot_m_s, double period_s,
                                  Eigen::VectorXd& force_n) {
  const Eigen::Index n = z_m.size();
  const double dt = period_s / static_cast<double>(n);
  const auto rows = static_cast<Eigen::Index>(terms_.size());
  a_.resize(rows, n);
  p_.resize(rows, n);
  q_.resize(rows, n);
  r_.resize(rows, n);
  w_.resize(rows, n);
  force_slope_.resize(rows, n);
  force_dz_.resize(rows, n);
  prefix_.resize(rows, n);
  states_.resize(rows, n);
  one_minus_a_.resize(rows);
  const auto keep = [&](Eigen::Index row, Eigen::Index k, const MarchStep& step) {
    a_(row, k) = step.a;
    p_(row, k) = step.dz0;
    q_(row, k) = step.dz1;
    r_(row, k) = step.dv0;
    w_(row, k) = step.dv1;
  };
  // Newton on each term's periodic state: march from s_0, then s_0 ← s_0 + g / (1 − A). Steps
  // that are affine in s (the Dahl element) make the update exact, and the states of the march
  // shift by P_k Δs_0 exactly, so one march suffices; other terms march again (at most 8 times).
  constexpr int kMaxMarches = 8;
  int marches = 0;
  for (Eigen::Index row = 0; row < rows; ++row) {
    const std::size_t t = terms_[static_cast<std::size_t>(row)];
    const ModelTerm& term = *model.terms()[t];
    double s0 = 0.0;
    term.initial_state(z_m[0], &s0);
    for (int iteration = 0; iteration < kMaxMarches; ++iteration) {
      ++marches;
      double s = s0, log_a = 0.0, product = 1.0;
      bool logs = true, affine = true;
      for (Eigen::Index k = 0; k < n; ++k) {
        const Eigen::Index next = (k + 1) % n;
        prefix_(row, k) = product;
        states_(row, k) = s;
        const MarchStep step =
            march_step(term, z_m[k], z_dot_m_s[k], z_m[next], z_dot_m_s[next], dt, s);
        keep(row, k, step);
        product *= step.a;
        affine = affine && step.affine;
        if (step.a > 0.0) {
          log_a += step.log_a;
        } else {
          logs = false;
        }
      }
      one_minus_a_[row] = logs ? -std::expm1(log_a) : 1.0 - product;
      const double g = s - s0;
      if (std::abs(g) <= tolerance_ || !(one_minus_a_[row] > 0.0)) break;
      const double shift = g / one_minus_a_[row];
      s0 += shift;
      if (affine) {
        // The periodic states, and the step sensitivities again along them (∂s₁/∂z depends
        // on s₀; ∂s₁/∂s₀ and the prefix products do not, for affine steps).
        for (Eigen::Index k = 0; k < n; ++k) {
          const Eigen::Index next = (k + 1) % n;
          double s_k = states_(row, k) + shift * prefix_(row, k);
          states_(row, k) = s_k;
          keep(row, k, march_step(term, z_m[k], z_dot_m_s[k], z_m[next], z_dot_m_s[next], dt, s_k));
        }
        break;
      }
    }
    for (Eigen::Index k = 0; k < n; ++k) {
      double s = states_(row, k);
      force_n[k] += state_part(term, z_m[k], z_dot_m_s[k], &s);
      force_slope_(row, k) = term.force_d_state(z_m[k], z_dot_m_s[k], &s);
      force_dz_(row, k) = term.partials(z_m[k], z_dot_m_s[k], &s).d_dz -
                          term.partials(z_m[k], z_dot_m_s[k], nullptr).d_dz;
    }
  }
  return marches;
}

void HysteresisMarch::sensitivity(const Eigen::MatrixXd& dz_m, const Eigen::MatrixXd& dz_dot_m_s,
                                  Eigen::MatrixXd& dforce_n) const {
  const Eigen::Index n = dz_m.cols();
  dforce_n.setZero(dz_m.rows(), n);
  Eigen::VectorXd u(dz_m.rows());
  for (Eigen::Index row = 0; row < a_.rows(); ++row) {
    // u_k: the recurrence from u_0 = 0 (all directions at once); then δs_0 = u_N / (1 − A) and
    // δs_k = u_k + P_k δs_0.
    u.setZero();
    for (Eigen::Index k = 0; k < n; ++k) {
      const Eigen::Index next = (k + 1) % n;
      dforce_n.col(k) += force_slope_(row, k) * u;  // the u_k part now, the P_k δs_0 part below
      if (force_dz_(row, k) != 0.0) dforce_n.col(k) += force_dz_(row, k) * dz_m.col(k);
      u = a_(row, k) * u + p_(row, k) * dz_m.col(k) + q_(row, k) * dz_m.col(next);
      if (r_(row, k) != 0.0 || w_(row, k) != 0.0) {
        u += r_(row, k) * dz_dot_m_s.col(k) + w_(row, k) * dz_dot_m_s.col(next);
      }
    }
    if (!(one_minus_a_[row] > 0.0)) continue;
    const Eigen::VectorXd ds0 = u / one_minus_a_[row];
    for (Eigen::Index k = 0; k < n; ++k) {
      const double weight = force_slope_(row, k) * prefix_(row, k);
      if (weight != 0.0) dforce_n.col(k) += weight * ds0;
    }
  }
}

int HysteresisMarch::marched_forces(const Model& model, const Eigen::VectorXd& z_m,
                                    const Eigen::VectorXd& z_dot_m_s, double period_s,
                                    Eigen::VectorXd& force_n) {
  const Eigen::Index n = z_m.size();
  const double dt = period_s / static_cast<double>(n);

  // Start at the first upward crossing of the mean (index of the sample after it).
  const double mean = z_m.mean();
  Eigen::Index first = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (z_m[k] <= mean && z_m[(k + 1) % n] > mean) {
      first = (k + 1) % n;
      break;
    }
  }
  for (std::size_t t : terms_) {
    model.terms()[t]->initial_state(z_m[first], state_.data() + model.state_offset(t));
  }

  int periods = 0;
  for (; periods < max_periods_; ++periods) {
    start_of_period_ = state_;
    for (Eigen::Index step = 0; step < n; ++step) {
      const Eigen::Index k = (first + step) % n;
      const Eigen::Index next = (k + 1) % n;
      for (std::size_t t : terms_) {
        model.terms()[t]->advance_state(z_m[k], z_dot_m_s[k], z_m[next], z_dot_m_s[next], dt,
                                        state_.data() + model.state_offset(t));
      }
      // The force at sample `next` from the state just reached.
      double force = 0.0;
      for (std::size_t t : terms_) {
        force += state_part(*model.terms()[t], z_m[next], z_dot_m_s[next],
                            state_.data() + model.state_offset(t));
      }
      force_n[next] = force;
    }
    double change = 0.0;
    for (std::size_t i = 0; i < state_.size(); ++i) {
      change = std::max(change, std::abs(state_[i] - start_of_period_[i]));
    }
    if (periods >= 1 && change <= tolerance_) return periods + 1;
  }
  return periods;
}

}  // namespace oscilab::analysis

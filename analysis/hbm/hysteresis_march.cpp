#include "analysis/hbm/hysteresis_march.h"

#include <algorithm>
#include <cmath>

namespace oscilab::analysis {

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
  return exact_ ? exact_forces(model, z_m, z_dot_m_s, force_n)
                : marched_forces(model, z_m, z_dot_m_s, period_s, force_n);
}

int HysteresisMarch::exact_forces(const Model& model, const Eigen::VectorXd& z_m,
                                  const Eigen::VectorXd& z_dot_m_s, Eigen::VectorXd& force_n) {
  const Eigen::Index n = z_m.size();
  const auto rows = static_cast<Eigen::Index>(terms_.size());
  a_.resize(rows, n);
  p_.resize(rows, n);
  q_.resize(rows, n);
  force_slope_.resize(rows, n);
  prefix_.resize(rows, n);
  states_.resize(rows, n);
  one_minus_a_.resize(rows);
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
        StateStepSensitivity step;
        prefix_(row, k) = product;
        states_(row, k) = s;
        term.advance_state_sensitivity(z_m[k], z_m[(k + 1) % n], &s, step);
        a_(row, k) = step.d_state;
        p_(row, k) = step.d_z0;
        q_(row, k) = step.d_z1;
        product *= step.d_state;
        affine = affine && step.affine;
        if (step.d_state > 0.0) {
          log_a += step.log_d_state;
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
          double s_k = states_(row, k) + shift * prefix_(row, k);
          states_(row, k) = s_k;
          StateStepSensitivity step;
          term.advance_state_sensitivity(z_m[k], z_m[(k + 1) % n], &s_k, step);
          p_(row, k) = step.d_z0;
          q_(row, k) = step.d_z1;
        }
        break;
      }
    }
    for (Eigen::Index k = 0; k < n; ++k) {
      double s = states_(row, k);
      force_n[k] += term.force(z_m[k], z_dot_m_s[k], &s);
      force_slope_(row, k) = term.force_d_state(z_m[k], z_dot_m_s[k], &s);
    }
  }
  return marches;
}

void HysteresisMarch::sensitivity(const Eigen::MatrixXd& dz_m, Eigen::MatrixXd& dforce_n) const {
  const Eigen::Index n = dz_m.cols();
  dforce_n.setZero(dz_m.rows(), n);
  Eigen::VectorXd u(dz_m.rows());
  for (Eigen::Index row = 0; row < a_.rows(); ++row) {
    // u_k: the recurrence from u_0 = 0 (all directions at once); then δs_0 = u_N / (1 − A) and
    // δs_k = u_k + P_k δs_0.
    u.setZero();
    for (Eigen::Index k = 0; k < n; ++k) {
      dforce_n.col(k) += force_slope_(row, k) * u;  // the u_k part now, the P_k δs_0 part below
      u = a_(row, k) * u + p_(row, k) * dz_m.col(k) + q_(row, k) * dz_m.col((k + 1) % n);
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
        force += model.terms()[t]->force(z_m[next], z_dot_m_s[next],
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

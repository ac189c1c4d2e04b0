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
  one_minus_a_.resize(rows);
  // Newton on each term's periodic state. Every step of the Dahl element is affine in s, so the
  // first update is exact and the second march only confirms it; 8 marches bound a term whose
  // steps are not affine.
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
      bool logs = true;
      for (Eigen::Index k = 0; k < n; ++k) {
        StateStepSensitivity step;
        prefix_(row, k) = product;
        force_slope_(row, k) = term.force_d_state(z_m[k], z_dot_m_s[k], &s);
        term.advance_state_sensitivity(z_m[k], z_m[(k + 1) % n], &s, step);
        a_(row, k) = step.d_state;
        p_(row, k) = step.d_z0;
        q_(row, k) = step.d_z1;
        product *= step.d_state;
        if (step.d_state > 0.0) {
          log_a += std::log(step.d_state);
        } else {
          logs = false;
        }
      }
      one_minus_a_[row] = logs ? -std::expm1(log_a) : 1.0 - product;
      const double g = s - s0;
      if (std::abs(g) <= tolerance_ || !(one_minus_a_[row] > 0.0)) break;
      s0 += g / one_minus_a_[row];
    }
    // The forces along the periodic state.
    double s = s0;
    for (Eigen::Index k = 0; k < n; ++k) {
      force_n[k] += term.force(z_m[k], z_dot_m_s[k], &s);
      StateStepSensitivity step;
      term.advance_state_sensitivity(z_m[k], z_m[(k + 1) % n], &s, step);
    }
  }
  return marches;
}

void HysteresisMarch::sensitivity(const Eigen::VectorXd& dz_m, Eigen::VectorXd& dforce_n) const {
  const Eigen::Index n = dz_m.size();
  dforce_n.setZero(n);
  for (Eigen::Index row = 0; row < a_.rows(); ++row) {
    // u_k: the recurrence from u_0 = 0; then δs_0 = u_N / (1 − A) and δs_k = u_k + P_k δs_0.
    double u = 0.0;
    for (Eigen::Index k = 0; k < n; ++k) {
      dforce_n[k] += force_slope_(row, k) * u;  // the u_k part now, the P_k δs_0 part below
      u = a_(row, k) * u + p_(row, k) * dz_m[k] + q_(row, k) * dz_m[(k + 1) % n];
    }
    if (!(one_minus_a_[row] > 0.0)) continue;
    const double ds0 = u / one_minus_a_[row];
    for (Eigen::Index k = 0; k < n; ++k) dforce_n[k] += force_slope_(row, k) * prefix_(row, k) * ds0;
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

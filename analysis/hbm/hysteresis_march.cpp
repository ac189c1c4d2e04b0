#include "analysis/hbm/hysteresis_march.h"

#include <algorithm>
#include <cmath>

namespace oscilab::analysis {

HysteresisMarch::HysteresisMarch(const Model& model, double tolerance, int max_periods)
    : tolerance_(tolerance), max_periods_(max_periods) {
  for (std::size_t i = 0; i < model.terms().size(); ++i) {
    if (model.terms()[i]->state_size() > 0) terms_.push_back(i);
  }
  state_.assign(static_cast<std::size_t>(model.state_size()), 0.0);
  start_of_period_ = state_;
}

int HysteresisMarch::forces(const Model& model, const Eigen::VectorXd& z_m,
                            const Eigen::VectorXd& z_dot_m_s, double period_s,
                            Eigen::VectorXd& force_n) {
  const Eigen::Index n = z_m.size();
  force_n.setZero(n);
  if (!active() || n == 0) return 0;
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

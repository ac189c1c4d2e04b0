#include "analysis/design/model_weights.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace oscilab::analysis {

std::vector<double> bic_weights(const std::vector<double>& bic) {
  double smallest = std::numeric_limits<double>::infinity();
  for (double b : bic) {
    if (std::isfinite(b)) smallest = std::min(smallest, b);
  }
  std::vector<double> out(bic.size(), 0.0);
  if (!std::isfinite(smallest)) return out;
  double sum = 0.0;
  for (std::size_t i = 0; i < bic.size(); ++i) {
    // exp(−ΔBIC/2) with ΔBIC ≥ 0: the smallest BIC gets 1 before normalising, so nothing
    // overflows and the leader never underflows.
    if (std::isfinite(bic[i])) out[i] = std::exp(-0.5 * (bic[i] - smallest));
    sum += out[i];
  }
  for (double& w : out) w /= sum;
  return out;
}

void update_weights(std::vector<ModelHypothesis>& hypotheses) {
  std::vector<double> bic;
  for (const ModelHypothesis& h : hypotheses) {
    bic.push_back(h.solved ? h.bic : std::numeric_limits<double>::infinity());
  }
  const std::vector<double> w = bic_weights(bic);
  for (std::size_t i = 0; i < hypotheses.size(); ++i) hypotheses[i].weight = w[i];
}

int leading_hypothesis(const std::vector<ModelHypothesis>& hypotheses) {
  int leader = -1;
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    if (!hypotheses[i].solved) continue;
    if (leader < 0 || hypotheses[i].weight > hypotheses[static_cast<std::size_t>(leader)].weight) {
      leader = static_cast<int>(i);
    }
  }
  return leader;
}

double noise_reduced_chi2(int dof) {
  return dof > 0 ? 1.0 + 3.0 * std::sqrt(2.0 / dof) : std::numeric_limits<double>::quiet_NaN();
}

StopDecision stop_decision(const std::vector<ModelHypothesis>& hypotheses, const StopRule& rule,
                           double shaker_time_s, double max_discrimination) {
  StopDecision out;
  out.leader = leading_hypothesis(hypotheses);
  char text[320];
  if (out.leader >= 0) {
    const ModelHypothesis& leader = hypotheses[static_cast<std::size_t>(out.leader)];
    out.leader_weight = leader.weight;
    out.reduced_chi2 = leader.reduced_edc_chi2();
    out.noise_reduced_chi2 = noise_reduced_chi2(leader.levels - leader.parameters());
    out.gap_at_noise = out.reduced_chi2 <= out.noise_reduced_chi2;    // false for NaN
    out.nothing_left = max_discrimination < rule.min_discrimination;  // false for NaN
    out.decided = out.gap_at_noise && (out.leader_weight >= rule.leader_weight || out.nothing_left);
    std::snprintf(text, sizeof text, "leader %s, weight %.4f (stop at %.2f), ",
                  leader.label().c_str(), out.leader_weight, rule.leader_weight);
    out.reason = text;
    if (std::isfinite(out.noise_reduced_chi2)) {
      std::snprintf(text, sizeof text, "chi2/dof %.3g against the noise level %.3g",
                    out.reduced_chi2, out.noise_reduced_chi2);
    } else {  // ν ≤ 0: no misfit to judge yet
      std::snprintf(text, sizeof text,
                    "its misfit cannot be judged yet (levels %d, parameters %d: it needs more "
                    "levels than parameters)",
                    leader.levels, leader.parameters());
    }
    out.reason += text;
    if (std::isfinite(max_discrimination)) {
      std::snprintf(text, sizeof text,
                    "; the best setting separates two plausible models by %.2g (stop below %.2g)",
                    max_discrimination, rule.min_discrimination);
      out.reason += text;
    }
  } else {
    out.reason = "no hypothesis solved";
  }
  if (out.decided) {
    out.stop = true;
    out.reason = "decided: " + out.reason;
  } else if (shaker_time_s >= rule.budget_s) {
    out.stop = true;
    std::snprintf(text, sizeof text, "budget: shaker time %.1f s reached %.1f s; ", shaker_time_s,
                  rule.budget_s);
    out.reason = text + out.reason;
  }
  return out;
}

}  // namespace oscilab::analysis

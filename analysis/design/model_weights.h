#pragma once

#include <limits>
#include <string>
#include <vector>

#include "analysis/design/model_hypothesis.h"

namespace oscilab::analysis {

/// Posterior model probabilities from BIC (Schwarz 1978; Kass & Raftery 1995, "Bayes factors",
/// §4.1.3): with equal prior odds, p(M_i | data) ≈ exp(−BIC_i/2) / Σ_j exp(−BIC_j/2), computed as
/// the softmax of −ΔBIC/2 against the smallest BIC. Non-finite BICs (an unsolved model) get 0.
std::vector<double> bic_weights(const std::vector<double>& bic);

/// Sets every hypothesis's weight from its BIC (bic_weights); unsolved ones get 0.
void update_weights(std::vector<ModelHypothesis>& hypotheses);

/// The hypothesis of the largest weight (-1 when none is solved).
int leading_hypothesis(const std::vector<ModelHypothesis>& hypotheses);

/// When an adaptive test stops. Decided: the leading model's own EDC misfit is at the noise level
/// (χ²/ν ≤ 1 + 3√(2/ν), three standard deviations of a correct model's reduced χ², as the
/// diagnosis's noise level) and either its weight is ≥ `leader_weight`, or no admissible setting
/// is expected to tell two plausible models apart by more than `min_discrimination`
/// (NextPoint::max_discrimination; 1: one σ of a measurement). The second is how a test whose
/// truth is the baseline ends: nested candidates fitted to its data predict what it predicts,
/// while BIC's Occam factor (√n per parameter) would need thousands of levels to give the
/// baseline a weight of 0.99 over seven candidates. Otherwise the budget: the shaker time
/// reached `budget_s`.
struct StopRule {
  double leader_weight = 0.99;
  double min_discrimination = 1.0;
  double budget_s = 600.0;  // shaker time, s
};

struct StopDecision {
  bool stop = false;
  bool decided = false;  // stopped because a leader is clear, not for the budget
  int leader = -1;
  double leader_weight = 0.0;
  double reduced_chi2 = 0.0;        // the leader's χ²_EDC / ν
  double noise_reduced_chi2 = 0.0;  // 1 + 3√(2/ν); NaN when ν ≤ 0
  bool gap_at_noise = false;
  bool nothing_left = false;  // max_discrimination below the rule's minimum
  std::string reason;         // in words, always set
};

/// The noise level of a reduced χ² with ν degrees of freedom: 1 + 3√(2/ν) (NaN for ν ≤ 0).
double noise_reduced_chi2(int dof);

/// `max_discrimination`: NextPoint::max_discrimination of the proposal at this point, NaN when
/// none was made (then only the leader's weight decides).
StopDecision stop_decision(const std::vector<ModelHypothesis>& hypotheses, const StopRule& rule,
                           double shaker_time_s,
                           double max_discrimination = std::numeric_limits<double>::quiet_NaN());

}  // namespace oscilab::analysis

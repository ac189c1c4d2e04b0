#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/design/adaptive_test.h"

namespace oscilab::analysis {

/// One line of an adaptive test's decision log (docs/contracts.md, `decisions.jsonl`): the
/// decision's index, times and levels, every hypothesis's weight and fit, the leader and the
/// stop rule's answer, `reason` in words, and when the test goes on the `proposal` with every
/// setting's `scores`.
nlohmann::json adaptive_decision_json(const AdaptiveDecision& decision,
                                      const std::vector<ModelHypothesis>& hypotheses);

/// An adaptive test's report.json: the final diagnosis's report (diagnosis_report_json of
/// `records`, the recordings made) with its `notes`, `shaker_time_s`, and `adaptive_test`: the
/// levels, the loop's own answer (leader, stop reason, weights) and whether the diagnosis agrees.
/// Without a final diagnosis (switched off or cancelled): `records`, `status` ("ok",
/// "cancelled") and the last two. `bic_threshold`: the diagnosis's
/// (DiagnosisOptions::bic_threshold).
nlohmann::json adaptive_test_report_json(const AdaptiveTestResult& result,
                                         const std::vector<std::string>& records,
                                         double bic_threshold = 10.0);

}  // namespace oscilab::analysis

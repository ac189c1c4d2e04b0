#include "analysis/design/adaptive_test_report.h"

namespace oscilab::analysis {
namespace {

nlohmann::json weights_json(const std::vector<ModelHypothesis>& hypotheses) {
  nlohmann::json out = nlohmann::json::object();
  for (const ModelHypothesis& h : hypotheses) out[h.label()] = h.weight;
  return out;
}

nlohmann::json fits_json(const std::vector<ModelHypothesis>& hypotheses) {
  nlohmann::json out = nlohmann::json::object();
  for (const ModelHypothesis& h : hypotheses) {
    out[h.label()] = {{"edc", h.edc_chi2},
                      {"joint", h.joint_chi2},
                      {"bic", h.bic},
                      {"parameters", h.parameters()},
                      {"solved", h.solved}};
    if (!h.message.empty()) out[h.label()]["message"] = h.message;
  }
  return out;
}

nlohmann::json setting_json(const SettingScore& s) {
  return {{"f0_n", s.f0_n},
          {"freq_hz", s.freq_hz},
          {"well", s.positive_well ? "positive" : "negative"},
          {"admissible", s.admissible},
          {"criterion", s.criterion},
          {"criterion_per_s", s.criterion_per_s},
          {"shaker_s", s.shaker_s}};
}

}  // namespace

nlohmann::json adaptive_decision_json(const AdaptiveDecision& d,
                                      const std::vector<ModelHypothesis>& hypotheses) {
  const StopDecision& stop = d.decision;
  nlohmann::json line = {
      {"decision", d.index},
      {"time_s", d.time_s},
      {"shaker_time_s", d.shaker_time_s},
      {"levels", d.levels},
      {"weights", weights_json(hypotheses)},
      {"fits", fits_json(hypotheses)},
      {"leader", stop.leader >= 0 ? hypotheses[static_cast<std::size_t>(stop.leader)].label() : ""},
      {"leader_weight", stop.leader_weight},
      {"reduced_chi2", stop.reduced_chi2},
      {"noise_reduced_chi2", stop.noise_reduced_chi2},
      {"max_discrimination", d.next.found ? d.next.max_discrimination : 0.0},
      {"proposal_s", d.proposal_s},
      {"refit_s", d.refit_s},
      {"stop", stop.stop},
      {"reason", stop.stop ? stop.reason : d.next.reason}};
  if (!stop.stop) {
    line["proposal"] = setting_json(d.next.best);
    nlohmann::json scores = nlohmann::json::array();
    for (const SettingScore& s : d.next.settings) scores.push_back(setting_json(s));
    line["scores"] = scores;
  }
  return line;
}

nlohmann::json adaptive_test_report_json(const AdaptiveTestResult& result,
                                         const std::vector<std::string>& records,
                                         double bic_threshold) {
  nlohmann::json report = nlohmann::json::object();
  if (result.diagnosed) {
    report = diagnosis_report_json(result.diagnosis, records, bic_threshold);
    report["notes"] = result.notes;
  } else {
    report["records"] = records;
    report["status"] = result.status == JobStatus::Cancelled ? "cancelled" : "ok";
  }
  report["shaker_time_s"] = result.shaker_time_s;
  // The loop's own answer beside the diagnosis's: on a few levels a diagnosis's candidate refits,
  // started from its baseline, can miss a fit the loop's global searches found.
  const std::string leader = result.leader();
  nlohmann::json adaptive = {{"levels", result.levels},
                             {"pilot_levels_per_well", result.pilot_levels_per_well},
                             {"adaptive_levels", result.adaptive_levels},
                             {"decided", result.decision.decided},
                             {"stop_reason", result.decision.reason},
                             {"leader", leader},
                             {"leader_reduced_chi2", result.decision.reduced_chi2},
                             {"weights", weights_json(result.hypotheses)},
                             {"seconds", result.seconds}};
  if (result.diagnosed) adaptive["agrees_with_diagnosis"] = leader == result.diagnosis.verdict;
  report["adaptive_test"] = adaptive;
  return report;
}

}  // namespace oscilab::analysis

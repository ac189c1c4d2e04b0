#include "analysis/diagnosis/diagnosis_progress.h"

#include <string>

namespace oscilab::analysis {

const char* to_string(DiagnosisPhase phase) {
  switch (phase) {
    case DiagnosisPhase::Baseline:
      return "baseline";
    case DiagnosisPhase::Settling:
      return "settling";
    case DiagnosisPhase::Candidates:
      return "candidates";
    case DiagnosisPhase::Finalists:
      return "finalists";
    case DiagnosisPhase::Accepting:
      return "accepting";
    case DiagnosisPhase::Done:
      return "done";
  }
  return "unknown";
}

std::string DiagnosisProgress::describe() const {
  const std::string step_text =
      "step " + std::to_string(step) + " of at most " + std::to_string(max_steps) + ": ";
  switch (phase) {
    case DiagnosisPhase::Baseline:
      return "baseline: global search, " + std::to_string(evaluations) + " of " +
             std::to_string(baseline_budget) + " evaluations";
    case DiagnosisPhase::Settling:
      return step == 0 ? "settling the baseline" : step_text + "settling the model";
    case DiagnosisPhase::Candidates:
      return step_text + std::to_string(candidates_done) + " of " + std::to_string(candidates) +
             " candidates refitted" + (candidate.empty() ? "" : " (last: " + candidate + ")");
    case DiagnosisPhase::Finalists:
      return step_text + "longer refits of the leading candidates";
    case DiagnosisPhase::Accepting:
      return step_text + "settling the model with " + candidate;
    case DiagnosisPhase::Done:
      return "done";
  }
  return {};
}

}  // namespace oscilab::analysis

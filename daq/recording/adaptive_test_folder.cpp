#include "daq/recording/adaptive_test_folder.h"

#include <filesystem>
#include <utility>

#include <nlohmann/json.hpp>

#include "analysis/common/input_error.h"
#include "analysis/design/adaptive_test_report.h"
#include "daq/recording/json_file.h"

namespace oscilab::daq {

AdaptiveTestFolder::AdaptiveTestFolder(std::string dir) : dir_(std::move(dir)) {
  std::error_code error;
  std::filesystem::create_directories(recordings_dir(), error);
  if (error) throw InputError(dir_ + ": cannot create: " + error.message());
  log_.open(dir_ + "/decisions.jsonl", std::ios::trunc);
  if (!log_) throw InputError(dir_ + "/decisions.jsonl: cannot write");
}

void AdaptiveTestFolder::log(const analysis::AdaptiveDecision& decision,
                             const std::vector<analysis::ModelHypothesis>& hypotheses) {
  log_ << analysis::adaptive_decision_json(decision, hypotheses).dump() << '\n';
  log_.flush();
  if (!log_) throw InputError(dir_ + "/decisions.jsonl: cannot write (disk full?)");
}

void AdaptiveTestFolder::write_results(const analysis::AdaptiveTestResult& result,
                                       const std::vector<std::string>& recordings) const {
  if (result.diagnosis.final_form) {
    const nlohmann::json model =
        result.diagnosis.final_form->build(result.diagnosis.final_theta).to_json();
    write_text_file_atomically(model.dump(2) + '\n', dir_ + "/final_model.json");
  }
  const nlohmann::json report = analysis::adaptive_test_report_json(result, recordings);
  write_text_file_atomically(report.dump(2) + '\n', dir_ + "/report.json");
}

}  // namespace oscilab::daq

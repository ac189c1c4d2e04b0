#pragma once
// The folder an adaptive test writes, the same from the CLI, the app and Python.

#include <fstream>
#include <string>
#include <vector>

#include "analysis/design/adaptive_test.h"

namespace oscilab::daq {

/// DIR/recordings/ (the runs, written by the level runner), DIR/decisions.jsonl (one JSON line
/// per decision, flushed as it is made: a test cut short keeps every decision made), and at the
/// end DIR/final_model.json (the final diagnosis's model, when there is one) and DIR/report.json,
/// each written whole through a temporary file and a rename. Every failure is one InputError
/// naming the file. Not thread-safe: one test per folder.
class AdaptiveTestFolder {
 public:
  /// Creates DIR and DIR/recordings and opens the decision log (a log already there is
  /// replaced).
  explicit AdaptiveTestFolder(std::string dir);

  const std::string& dir() const { return dir_; }
  std::string recordings_dir() const { return dir_ + "/recordings"; }

  /// Appends the decision's line (adaptive_decision_json) and flushes it.
  void log(const analysis::AdaptiveDecision& decision,
           const std::vector<analysis::ModelHypothesis>& hypotheses);

  /// Writes final_model.json (if the diagnosis has a final model) and then report.json
  /// (adaptive_test_report_json of the result and the recordings made).
  void write_results(const analysis::AdaptiveTestResult& result,
                     const std::vector<std::string>& recordings) const;

 private:
  std::string dir_;
  std::ofstream log_;
};

}  // namespace oscilab::daq

// The adaptive test's loop (run_adaptive_test) on the virtual rig, small enough for the unit
// suite: its options refused before any run, the shaker time it books against what the runs and
// the changes of well took, the decisions it reports, the operator's skip and stop, and a cancel
// between runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/design/adaptive_test.h"
#include "analysis/design/adaptive_test_report.h"
#include "analysis/model/reference_models.h"
#include "daq/recording/adaptive_test_folder.h"
#include "daq/recording/json_file.h"
#include "daq/rig/rig_level_runner.h"
#include "tests/analysis/design/small_adaptive_test.h"

namespace oscilab::analysis {
namespace {

// The rig, with every call counted and its shaker time kept, and a hook before each run.
class CountingRunner : public LevelRunner {
 public:
  explicit CountingRunner(const std::string& folder) : rig_(truth(), folder, {6.0, 1.0, 2.5}, 7) {}

  LevelRun run(const std::vector<double>& levels_n, double freq_hz, bool positive_well,
               const std::string& purpose) override {
    if (before_run) before_run(static_cast<int>(calls.size()));
    calls.push_back({levels_n, freq_hz, positive_well, purpose});
    LevelRun out = rig_.run(levels_n, freq_hz, positive_well, purpose);
    run_shaker_s += out.shaker_s;
    return out;
  }

  struct Call {
    std::vector<double> levels_n;
    double freq_hz;
    bool positive_well;
    std::string purpose;
  };
  std::vector<Call> calls;
  double run_shaker_s = 0.0;
  std::function<void(int)> before_run;

 private:
  static Model truth() { return testing::quadratic_damping_truth(); }
  daq::RigLevelRunner rig_;
};

std::string temporary_folder(const std::string& name) {
  const std::string folder =
      (std::filesystem::temp_directory_path() / ("oscilab_adaptive_" + name)).string();
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

AdaptiveTestOptions small_options() { return testing::small_adaptive_test_options(); }

TEST(AdaptiveTest, RefusesBadOptionsNamingTheFieldBeforeAnyRun) {
  CountingRunner runner(temporary_folder("refused"));
  const auto refused = [&](AdaptiveTestOptions o, const std::string& field) {
    try {
      run_adaptive_test(runner, o);
      ADD_FAILURE() << field << ": accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  AdaptiveTestOptions o = small_options();
  o.pilot_levels_n = {};
  refused(o, "pilot_levels_n");
  o = small_options();
  o.pilot_levels_n = {1.0, -0.5};
  refused(o, "pilot_levels_n");
  o = small_options();
  o.stop.leader_weight = 1.5;
  refused(o, "stop.leader_weight");
  o = small_options();
  o.stop.budget_s = 0.0;
  refused(o, "stop.budget_s");
  o = small_options();
  o.hypotheses.effects = {"quadratic-damping", "drag"};
  refused(o, "unknown effect \"drag\"");
  o = small_options();
  o.hypotheses.refit_evaluations = 3;
  refused(o, "refit_evaluations");
  o = small_options();
  o.max_levels = 0;
  refused(o, "max_levels");
  o = small_options();
  o.settings.freq_step_hz = 0.0;
  refused(o, "settings.freq_step_hz: must be a positive number of Hz");
  o = small_options();
  o.settings.f0_min_n = 3.0;  // above f0_max_n
  refused(o, "settings.f0_range_n: need 0 < f0_min <= f0_max");
  EXPECT_TRUE(runner.calls.empty());
}

TEST(AdaptiveTest, ARefusalNamesTheFieldAsTheCallerCallsIt) {
  const std::vector<std::pair<std::string, std::string>> names = {{"stop.budget_s", "--budget"},
                                                                  {"settings.freq_hz", "--freq"}};
  const auto message = [&](const AdaptiveTestOptions& o) {
    try {
      validate_as_named(o, names);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  AdaptiveTestOptions o = small_options();
  EXPECT_EQ(message(o), "accepted");
  o.stop.budget_s = -1.0;
  EXPECT_EQ(message(o), "--budget: must be a positive number of s");
  o = small_options();
  o.settings.freq_hz = 0.0;
  EXPECT_EQ(message(o), "--freq: must be a positive number of Hz");
  o = small_options();
  o.max_levels = 0;  // a field without a name keeps its own
  EXPECT_EQ(message(o), "max_levels: must be at least 1");
}

TEST(AdaptiveTest, BooksTheShakerTimeOfEveryRunAndWellChangeAndReportsEachDecision) {
  CountingRunner runner(temporary_folder("booked"));
  const AdaptiveTestOptions options = small_options();
  std::vector<AdaptiveDecision> decisions;
  std::vector<double> fractions;
  const AdaptiveTestResult result = run_adaptive_test(
      runner, options,
      [&](const AdaptiveDecision& d, const std::vector<ModelHypothesis>& h) {
        decisions.push_back(d);
        ASSERT_EQ(h.size(), 2u);  // the baseline and the one candidate
        EXPECT_EQ(h[0].effect, "none");
        EXPECT_EQ(h[1].effect, "quadratic-damping");
        EXPECT_NEAR(h[0].weight + h[1].weight, 1.0, 1e-12);
      },
      [&](double f) { fractions.push_back(f); });
  ASSERT_EQ(result.status, JobStatus::Ok) << result.message;
  // On four pilot levels with short fits the damping laws are not yet told apart: the loop runs
  // levels of its own (up to max_levels).
  ASSERT_GE(result.adaptive_levels, 1) << result.message;

  // The pilot, positive well first, then one run per adaptive level.
  ASSERT_EQ(runner.calls.size(), 2u + static_cast<std::size_t>(result.adaptive_levels));
  EXPECT_TRUE(runner.calls[0].positive_well);
  EXPECT_FALSE(runner.calls[1].positive_well);
  EXPECT_EQ(runner.calls[0].levels_n, options.pilot_levels_n);
  EXPECT_EQ(runner.calls[0].purpose, "pilot");
  int well_changes = 1;  // between the two pilots
  for (std::size_t i = 2; i < runner.calls.size(); ++i) {
    EXPECT_EQ(runner.calls[i].purpose, "level");
    ASSERT_EQ(runner.calls[i].levels_n.size(), 1u);
    well_changes += runner.calls[i].positive_well != runner.calls[i - 1].positive_well;
  }
  // Each run books its lead-in and dwells (the rig's schedule: 2.5 s + 6 s per level), each
  // change of well 10 s more; nothing else.
  EXPECT_NEAR(runner.run_shaker_s, 2 * (2.5 + 2 * 6.0) + result.adaptive_levels * (2.5 + 6.0),
              1e-9);
  EXPECT_NEAR(result.shaker_time_s, runner.run_shaker_s + 10.0 * well_changes, 1e-9);

  // One decision after the pilot and one after each adaptive level; only the last stops, and
  // each that goes on proposes the setting the next run was made at.
  ASSERT_EQ(decisions.size(), static_cast<std::size_t>(result.adaptive_levels) + 1);
  for (std::size_t i = 0; i < decisions.size(); ++i) {
    EXPECT_EQ(decisions[i].index, static_cast<int>(i));
    EXPECT_EQ(decisions[i].decision.stop, i + 1 == decisions.size());
    EXPECT_FALSE(decisions[i].decision.reason.empty());
    if (!decisions[i].decision.stop) {
      const SettingScore& p = decisions[i].next.best;
      EXPECT_DOUBLE_EQ(runner.calls[i + 2].levels_n[0], p.f0_n);
      EXPECT_EQ(runner.calls[i + 2].positive_well, p.positive_well);
      EXPECT_TRUE(p.admissible);
    }
  }
  EXPECT_NEAR(decisions.back().shaker_time_s, result.shaker_time_s, 1e-9);
  // Every level measured joins the dataset: the pilot's four and the adaptive ones.
  EXPECT_EQ(result.levels, 4 + result.adaptive_levels);
  EXPECT_EQ(decisions.back().levels, result.levels);
  // Progress never goes back and stays within the loop's share.
  ASSERT_FALSE(fractions.empty());
  for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_GE(fractions[i], fractions[i - 1]);
  EXPECT_LE(fractions.back(), 0.8);

  // The report carries the loop's answer; without a diagnosis, its own status.
  const nlohmann::json report = adaptive_test_report_json(result, {"a.wav"});
  EXPECT_EQ(report["status"], "ok");
  EXPECT_EQ(report["adaptive_test"]["levels"], result.levels);
  EXPECT_DOUBLE_EQ(report["shaker_time_s"].get<double>(), result.shaker_time_s);
  EXPECT_FALSE(report["adaptive_test"].contains("agrees_with_diagnosis"));
  // The decision log's line names the proposal of a decision that goes on.
  const nlohmann::json first = adaptive_decision_json(decisions.front(), result.hypotheses);
  EXPECT_EQ(first["stop"], decisions.front().decision.stop);
  EXPECT_EQ(first.contains("proposal"), !decisions.front().decision.stop);
}

TEST(AdaptiveTest, ACancelBetweenRunsReturnsWhatWasMeasured) {
  CountingRunner runner(temporary_folder("cancelled"));
  const CancelToken cancel;
  runner.before_run = [&](int call) {
    if (call == 1) cancel.cancel();  // while the negative well's pilot runs
  };
  const AdaptiveTestResult result = run_adaptive_test(runner, small_options(), {}, {}, cancel);
  EXPECT_EQ(result.status, JobStatus::Cancelled);
  EXPECT_EQ(runner.calls.size(), 2u);  // the run under way is finished, no other started
  EXPECT_EQ(result.runs.size(), 2u);
  EXPECT_FALSE(result.diagnosed);
  EXPECT_EQ(adaptive_test_report_json(result, {})["status"], "cancelled");
}

// The operator skips the first proposal: a new decision follows with no run between, proposing
// another setting; the gate is asked once per proposal, never for a decision that stops.
TEST(AdaptiveTest, ASkippedProposalIsNeverRunAndTheNextBestIsProposedWithoutALevel) {
  CountingRunner runner(temporary_folder("skipped"));
  std::vector<AdaptiveDecision> decisions;
  std::vector<std::size_t> runs_when_asked;
  int asked = 0;
  const AdaptiveTestResult result = run_adaptive_test(
      runner, small_options(),
      [&](const AdaptiveDecision& d, const std::vector<ModelHypothesis>&) {
        decisions.push_back(d);
      },
      {}, {},
      [&](const AdaptiveDecision& d) {
        EXPECT_FALSE(d.decision.stop);
        EXPECT_TRUE(d.next.found);
        runs_when_asked.push_back(runner.calls.size());
        return asked++ == 0 ? ProposalAnswer::Skip : ProposalAnswer::Run;
      });
  ASSERT_EQ(result.status, JobStatus::Ok) << result.message;
  ASSERT_GE(decisions.size(), 2u);
  // The skip: asked after the pilot's two runs, and asked again before any other run.
  ASSERT_GE(runs_when_asked.size(), 2u);
  EXPECT_EQ(runs_when_asked[0], 2u);
  EXPECT_EQ(runs_when_asked[1], 2u);
  const SettingScore& skipped = decisions[0].next.best;
  const SettingScore& instead = decisions[1].next.best;
  EXPECT_FALSE(skipped.f0_n == instead.f0_n && skipped.positive_well == instead.positive_well &&
               skipped.freq_hz == instead.freq_hz);
  // The setting skipped is never run, and the one proposed instead is the first level run.
  ASSERT_GE(runner.calls.size(), 3u);
  for (std::size_t i = 2; i < runner.calls.size(); ++i) {
    EXPECT_FALSE(runner.calls[i].levels_n[0] == skipped.f0_n &&
                 runner.calls[i].positive_well == skipped.positive_well &&
                 runner.calls[i].freq_hz == skipped.freq_hz);
  }
  EXPECT_DOUBLE_EQ(runner.calls[2].levels_n[0], instead.f0_n);
  EXPECT_EQ(runner.calls[2].positive_well, instead.positive_well);
  // The skip took no shaker time: both decisions stand at the pilot's.
  EXPECT_DOUBLE_EQ(decisions[1].shaker_time_s, decisions[0].shaker_time_s);
  EXPECT_EQ(decisions[1].levels, decisions[0].levels);
  // Every decision that goes on was put to the gate, and only those.
  int going_on = 0;
  for (const AdaptiveDecision& d : decisions) going_on += d.decision.stop ? 0 : 1;
  EXPECT_EQ(asked, going_on);
}

// The operator stops at the first proposal: nothing after the pilot is run, and the result says
// who stopped it.
TEST(AdaptiveTest, AStopFromTheOperatorEndsTheTestBeforeTheProposedLevel) {
  CountingRunner runner(temporary_folder("stopped"));
  int asked = 0;
  const AdaptiveTestResult result =
      run_adaptive_test(runner, small_options(), {}, {}, {}, [&](const AdaptiveDecision&) {
        ++asked;
        return ProposalAnswer::Stop;
      });
  ASSERT_EQ(result.status, JobStatus::Ok) << result.message;
  EXPECT_EQ(asked, 1);
  EXPECT_EQ(runner.calls.size(), 2u);
  EXPECT_EQ(result.adaptive_levels, 0);
  EXPECT_TRUE(result.decision.stop);
  EXPECT_FALSE(result.decision.decided);
  EXPECT_EQ(result.decision.reason.rfind("stopped by the operator; ", 0), 0u)
      << result.decision.reason;
}

// The folder of a test (the CLI's and the app's): one line per decision as it is made, then the
// report with the stop's reason; a folder that cannot be made is one line naming it.
TEST(AdaptiveTestFolder, HoldsEveryDecisionAndTheReportAndRefusesAFolderItCannotMake) {
  const std::string dir = temporary_folder("folder");
  daq::AdaptiveTestFolder folder(dir + "/test");
  CountingRunner runner(folder.recordings_dir());
  int decisions = 0;
  const AdaptiveTestResult result = run_adaptive_test(
      runner, small_options(),
      [&](const AdaptiveDecision& d, const std::vector<ModelHypothesis>& h) {
        folder.log(d, h);
        ++decisions;
      },
      {}, {}, [](const AdaptiveDecision&) { return ProposalAnswer::Stop; });
  folder.write_results(result, {"a.wav"});
  std::ifstream log(dir + "/test/decisions.jsonl");
  std::string line;
  int lines = 0;
  while (std::getline(log, line)) {
    EXPECT_EQ(nlohmann::json::parse(line)["decision"], lines);
    ++lines;
  }
  EXPECT_EQ(lines, decisions);
  EXPECT_EQ(lines, 1);
  const nlohmann::json report = daq::read_json_file(dir + "/test/report.json", 1 << 20);
  EXPECT_EQ(report["status"], "ok");
  EXPECT_EQ(report["adaptive_test"]["stop_reason"].get<std::string>().rfind("stopped by the "
                                                                            "operator",
                                                                            0),
            0u);
  EXPECT_FALSE(std::filesystem::exists(dir + "/test/final_model.json"));  // no diagnosis run

  std::ofstream(dir + "/plain_file") << "x";
  try {
    daq::AdaptiveTestFolder refused(dir + "/plain_file/test");
    ADD_FAILURE() << "a folder under a file was made";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind(dir + "/plain_file/test: cannot create: ", 0), 0u)
        << error.what();
  }
}

}  // namespace
}  // namespace oscilab::analysis

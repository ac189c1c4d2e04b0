#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/common/job.h"
#include "analysis/design/model_hypothesis.h"
#include "analysis/design/model_weights.h"
#include "analysis/design/next_point.h"
#include "analysis/diagnosis/diagnosis.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/pipeline/measurement_channels.h"
#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

/// One stepped-sine run the loop asked for and got: its channels (as offline analysis reads
/// them) and the shaker time it took (lead-in and every level's dwell).
struct LevelRun {
  MeasurementChannels channels;
  double shaker_s = 0.0;
};

/// What an adaptive test drives: runs a stepped sine of `levels_n` at `freq_hz` in one well and
/// hands the measurement back. The virtual rig is one (daq::RigLevelRunner); a shaker behind a
/// drive output is another. `purpose` is "pilot" or "level" (for names). Throws InputError when
/// the run cannot be made; the loop lets it through.
class LevelRunner {
 public:
  virtual ~LevelRunner() = default;
  virtual LevelRun run(const std::vector<double>& levels_n, double freq_hz, bool positive_well,
                       const std::string& purpose) = 0;
};

/// An adaptive test's settings: what it may choose from, how it starts, weighs and stops.
struct AdaptiveTestOptions {
  /// The f0 grid between the rig's limits, the frequencies, the wells, dwell, settling and the
  /// cost of a change of well.
  AdmissibleSettings settings;
  /// The pilot: these levels swept up in each admitted well (positive first) at
  /// settings.freq_hz, enough for every hypothesis's first fit.
  std::vector<double> pilot_levels_n{0.2, 1.0, 1.8, 2.7};
  StopRule stop;
  int max_levels = 40;  // adaptive levels after the pilot at most
  /// The base model of the form, its stiffness and the cost settings (as a fit's).
  FitSetup setup;
  HypothesisOptions hypotheses;  // its `cost` is set from `setup` by the loop
  NextPointOptions next;
  /// The final diagnosis of every recording made (diagnose, as on a fixed campaign's records);
  /// its `cost` is set from `setup`. Off: the loop's own weights are the answer.
  bool final_diagnosis = true;
  DiagnosisOptions diagnosis;

  /// Throws InputError naming the field ("stop.budget_s: …"): an empty or non-positive pilot, a
  /// leader weight outside (0.5, 1), a negative minimum discrimination, a non-positive budget, no
  /// adaptive level, fewer than 10 evaluations per fit, a negative global search, an unknown
  /// effect. Also settings.validate() ("settings.freq_hz: …").
  void validate() const;
};

/// options.validate(), its refusal naming the field as the caller's interface calls it: `names`
/// maps the fields of validate()'s messages to the caller's names (a CLI's options, Python's
/// keywords), so that "stop.budget_s: must be …" reaches a user as "--budget: must be …". A
/// field without a name keeps its own.
void validate_as_named(const AdaptiveTestOptions& options,
                       const std::vector<std::pair<std::string, std::string>>& names);

/// One decision of the loop, after the pilot and after every adaptive level: the hypotheses as
/// weighed then, the stop rule's answer and, when the test goes on, the proposal.
struct AdaptiveDecision {
  int index = 0;
  double time_s = 0.0;         // wall-clock time since the test started
  double shaker_time_s = 0.0;  // shaker time spent so far
  int levels = 0;              // levels measured (edc_dataset)
  StopDecision decision;
  NextPoint next;           // found == false when none was asked for (a stop by weight)
  double proposal_s = 0.0;  // wall-clock time of the proposal
  double refit_s = 0.0;     // of the refits after the last level (0 after the pilot)
};

struct AdaptiveTestResult {
  JobStatus status = JobStatus::Ok;  // Cancelled when the token was set
  std::string message;
  std::vector<ModelHypothesis> hypotheses;  // the baseline first, as last weighed
  StopDecision decision;                    // the last decision (the stop)
  std::vector<MeasurementChannels> runs;    // every run's channels, in order
  int pilot_levels_per_well = 0;
  int adaptive_levels = 0;
  int levels = 0;              // levels measured (edc_dataset of every run)
  double shaker_time_s = 0.0;  // runs plus changes of well
  /// The final diagnosis (AdaptiveTestOptions::final_diagnosis), of every run analysed afresh
  /// (analyze_campaign, with its slices), and the notes of its form (fit_form).
  bool diagnosed = false;
  DiagnosisResult diagnosis;
  std::vector<std::string> notes;
  double seconds = 0.0;  // wall-clock time of the whole test
  /// The loop's leading effect ("none" for the baseline or when nothing is solved).
  std::string leader() const;
};

/// Called with every decision, the hypotheses as weighed for it (for a decision log, a strip
/// chart of the weights). From the thread that runs the test.
using DecisionFn =
    std::function<void(const AdaptiveDecision&, const std::vector<ModelHypothesis>&)>;

/// What the operator answers to a proposal (ProposalGate).
enum class ProposalAnswer {
  Run,   // run the proposed level
  Skip,  // never this setting: the next best is proposed instead (a new decision)
  Stop,  // stop here: the test ends as when its stop rule says so (then the final diagnosis)
};

/// Asked with every proposal before it is run, from the thread that runs the test; it may block
/// until an operator answers (and must return when the test's token is cancelled). None: every
/// proposal is run (auto mode).
using ProposalGate = std::function<ProposalAnswer(const AdaptiveDecision&)>;

/// An adaptive stepped-sine test: the pilot in each well, then every hypothesis (the baseline
/// and each candidate effect, initial_hypotheses with a global search on the pilot) weighed; then
/// until the stop rule says so (stop_decision: a leader clear at the noise, nothing left to tell
/// apart, the shaker-time budget, max_levels, no admissible setting): the next point proposed
/// (propose_next_point), run, analysed as offline (analyze_record), every hypothesis refitted
/// warm (refit_hypotheses). A change of well costs settings.well_change_s of shaker time.
///
/// Then, unless switched off, the final diagnosis of every run (see AdaptiveTestResult).
///
/// `gate` sees each proposal first (ProposalGate): a skipped setting joins
/// NextPointOptions::skipped for the rest of the test and a new decision is made without a level;
/// a stop sets the last decision's `stop` (not `decided`) with the reason "stopped by the
/// operator".
///
/// Progress is the shaker time spent over the budget (up to 0.8), then the final diagnosis's;
/// `cancel` is polled between steps and inside the fits, proposals and the diagnosis, and returns
/// what was measured with status Cancelled.
/// Throws InputError for invalid options (validate) and what the runner or the first fits throw
/// (a pilot that yields no level).
AdaptiveTestResult run_adaptive_test(LevelRunner& runner, const AdaptiveTestOptions& options,
                                     const DecisionFn& on_decision = {},
                                     const ProgressFn& progress = {},
                                     const CancelToken& cancel = {}, const ProposalGate& gate = {});

}  // namespace oscilab::analysis

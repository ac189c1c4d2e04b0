// The diagnosis's progress as it runs: the phase, the step, the candidates refitted and the
// evaluations spent, turned into a never-decreasing fraction (DiagnosisProgress) and reported one
// at a time from the diagnosis's threads. Internal to the diagnosis (diagnosis.cpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnosis.h"

namespace oscilab::analysis {

// The diagnosis's progress: serialises the reports of its threads, counts the evaluations of the
// running candidates and keeps the fraction from going back.
class DiagnosisProgressTracker {
 public:
  DiagnosisProgressTracker(DiagnosisProgressFn report, const DiagnosisOptions& options)
      : report_(std::move(report)) {
    state_.max_steps = options.max_steps;
    state_.baseline_budget = options.baseline_evaluations;
  }

  void baseline_search(long evaluations) {
    update([&](DiagnosisProgress& p) {
      p.evaluations = evaluations;
      p.fraction = kBaselineSearchEnd *
                   std::min(1.0, static_cast<double>(evaluations) /
                                     static_cast<double>(std::max(1L, p.baseline_budget)));
    });
  }
  // A phase that starts at `step` (0: the baseline's) with `evaluations` done so far.
  void phase(DiagnosisPhase phase, int step, long evaluations, const std::string& candidate = {}) {
    update([&](DiagnosisProgress& p) {
      p.phase = phase;
      p.step = step;
      p.evaluations = evaluations;
      if (!candidate.empty()) p.candidate = candidate;
      done_before_ = evaluations;
      if (phase == DiagnosisPhase::Done) {
        p.fraction = 1.0;
      } else if (step == 0) {
        p.fraction = phase == DiagnosisPhase::Settling ? kBaselineSearchEnd : 0.0;
      } else if (phase == DiagnosisPhase::Finalists) {
        p.fraction = step_start(step) + kCandidatesShare * step_width();
      } else if (phase == DiagnosisPhase::Accepting) {
        p.fraction = step_start(step) + (kCandidatesShare + kFinalistsShare) * step_width();
      }
    });
  }
  void baseline_settled() {
    update([&](DiagnosisProgress& p) { p.fraction = kBaselineEnd; });
  }
  void candidates(int step, int count, long evaluations) {
    spent_.assign(static_cast<std::size_t>(count), 0);
    budget_ = 1;
    phase(DiagnosisPhase::Candidates, step, evaluations);
    update([&](DiagnosisProgress& p) {
      p.candidates = count;
      p.candidates_done = 0;
      p.candidate.clear();
      p.fraction = step_start(step);
    });
  }
  void set_trial_budget(long budget) { budget_ = std::max(1L, budget); }
  // Candidate `slot` has spent `evaluations` so far.
  void candidate_spent(std::size_t slot, long evaluations) {
    update([&](DiagnosisProgress& p) {
      if (slot < spent_.size()) spent_[slot] = evaluations;
      account(p);
    });
  }
  void candidate_done(std::size_t slot, const std::string& label) {
    update([&](DiagnosisProgress& p) {
      ++p.candidates_done;
      p.candidate = label;
      if (slot < spent_.size()) spent_[slot] = std::max(spent_[slot], budget_);
      account(p);
    });
  }

 private:
  // Shares of a step's part of the progress: refitting the candidates, the finalists' longer
  // refits, settling the model with the accepted effect; where the baseline's search and its
  // settling end.
  static constexpr double kCandidatesShare = 0.85, kFinalistsShare = 0.10;
  static constexpr double kBaselineSearchEnd = 0.20, kBaselineEnd = 0.25;

  double step_width() const { return (1.0 - kBaselineEnd) / std::max(1, state_.max_steps); }
  double step_start(int step) const { return kBaselineEnd + (step - 1) * step_width(); }
  // The candidates' evaluations and share of the step from what each has spent.
  void account(DiagnosisProgress& p) const {
    long total = 0;
    double share = 0.0;
    for (long s : spent_) {
      total += s;
      share += std::min(1.0, static_cast<double>(s) / static_cast<double>(budget_));
    }
    p.evaluations = done_before_ + total;
    p.fraction =
        step_start(p.step) + kCandidatesShare * step_width() * share /
                                 static_cast<double>(std::max<std::size_t>(1, spent_.size()));
  }
  template <class Change>
  void update(Change change) {
    const std::lock_guard lock(mutex_);
    const double before = state_.fraction;
    change(state_);
    state_.fraction = std::clamp(std::max(before, state_.fraction), 0.0, 1.0);
    if (report_) report_(state_);
  }

  DiagnosisProgressFn report_;
  std::mutex mutex_;
  DiagnosisProgress state_;
  std::vector<long> spent_;
  long budget_ = 1, done_before_ = 0;
};

}  // namespace oscilab::analysis

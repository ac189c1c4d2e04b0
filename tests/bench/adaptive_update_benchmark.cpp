// The adaptive test's work after each level (analysis/design/), what the loop does between one
// level and the next: every hypothesis refitted warm (refit_hypotheses: Levenberg–Marquardt from
// its last θ, the shared σ budget recalibrated) and the next point proposed (propose_next_point:
// every plausible hypothesis predicted by harmonic balance over the admissible grid, its
// parameters' uncertainty propagated, Box–Hill's criterion). Truth: the paper's model with
// quadratic damping (c2 = 6 N s²/m²) on the virtual rig; a pilot of four levels in each well and
// one adaptive level (1.2 N, positive well); hypotheses as the CLI's defaults weigh them (the
// baseline and every candidate of the vocabulary), first fitted without the global search (the
// benchmark times the update, not the pilot). Wall time of one update; the counters split it.
#include <chrono>
#include <vector>

#include <benchmark/benchmark.h>

#include "analysis/design/model_hypothesis.h"
#include "analysis/design/next_point.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/model/model_json.h"
#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace {

using namespace oscilab;
using namespace oscilab::analysis;
using Clock = std::chrono::steady_clock;

analysis::Model quadratic_damping_truth() {
  nlohmann::json json = paper_model().to_json();
  json["terms"].push_back({{"type", "quadratic-damping"}, {"c2_ns2_m2", 6.0}});
  return model_from_json(json, "benchmark truth");
}

RecordAnalysis rig_run(const Model& truth, std::vector<double> levels_n, bool positive,
                       std::uint64_t seed) {
  SteppedSineSchedule schedule;
  schedule.frequency_hz = 9.0;
  schedule.levels_n = std::move(levels_n);
  schedule.hold_s = 10.0;
  schedule.ramp_s = 1.0;
  daq::RigSpec spec;
  spec.positive_well = positive;
  spec.seed = seed;
  const daq::RigRecording rig = daq::record_stepped_sine(truth, schedule, spec);
  return analyze_record(daq::measurement_channels(rig.recording), PipelineSettings{});
}

struct Update {
  std::vector<ModelHypothesis> hypotheses;  // as weighed on the pilot
  EdcDataset after;                         // the pilot and the new level
  HypothesisOptions options;
  AdmissibleSettings settings;
  NextPointOptions next;
};

const Update& update() {
  static const Update made = [] {
    Update u;
    const Model truth = quadratic_damping_truth();
    CampaignAnalysis campaign;
    campaign.records.push_back(rig_run(truth, {0.2, 1.0, 1.8, 2.7}, true, 1000));
    campaign.records.push_back(rig_run(truth, {0.2, 1.0, 1.8, 2.7}, false, 1001));
    FitSetup setup;
    setup.base_model = paper_model();
    const PreparedFit prepared = prepare_fit(campaign, setup);
    u.options.cost = prepared.cost;
    u.options.global_evaluations = 0;
    const ModelForm& form = prepared.objective->form();
    u.hypotheses = initial_hypotheses(form, form.initial(), edc_dataset(campaign), u.options);
    campaign.records.push_back(rig_run(truth, {1.2}, true, 1002));
    u.after = edc_dataset(campaign);
    return u;
  }();
  return made;
}

void BM_AdaptiveUpdateAfterALevel(benchmark::State& state) {
  const Update& u = update();
  double refit_s = 0.0, proposal_s = 0.0;
  std::size_t hypotheses = 0;
  for (auto _ : state) {
    std::vector<ModelHypothesis> weighed = u.hypotheses;
    const auto start = Clock::now();
    refit_hypotheses(weighed, u.after, u.options);
    const auto refitted = Clock::now();
    const NextPoint next = propose_next_point(weighed, u.settings, u.next);
    benchmark::DoNotOptimize(next);
    refit_s = std::chrono::duration<double>(refitted - start).count();
    proposal_s = std::chrono::duration<double>(Clock::now() - refitted).count();
    hypotheses = weighed.size();
  }
  state.counters["hypotheses"] = double(hypotheses);
  state.counters["refit_s"] = refit_s;
  state.counters["proposal_s"] = proposal_s;
}
BENCHMARK(BM_AdaptiveUpdateAfterALevel)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();

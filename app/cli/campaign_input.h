#pragma once

#include <string>
#include <vector>

#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/measurement_mapping.h"

namespace oscilab::cli {

/// Where the input stage's time went (steady clock), and how much signal it read.
struct InputTimes {
  double read_s = 0.0;      // reading the files and their sidecars into channels
  double analysis_s = 0.0;  // the offline analysis of all records together
  double signal_s = 0.0;    // the records' total duration
};

/// How the input stage holds the records: in memory with everything the fits need (the
/// default), or streamed from their files keeping only what `retention` says (analyze).
struct InputStageOptions {
  bool streamed = false;
  analysis::OfflineRetention retention;
};

/// Reads the recordings (each with its sidecar) and runs the offline analysis of all of them
/// together, with a progress bar on a terminal: the input stage of analyze, fit and diagnose.
/// Throws InputError naming the file for a recording that cannot be read.
analysis::CampaignAnalysis run_input_stage(const std::vector<std::string>& paths,
                                           const daq::MappingOverrides& overrides,
                                           const analysis::PipelineSettings& settings,
                                           InputTimes* times = nullptr,
                                           const InputStageOptions& options = {});

}  // namespace oscilab::cli

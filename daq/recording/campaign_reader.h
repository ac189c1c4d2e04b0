#pragma once

#include <string>
#include <vector>

#include "analysis/common/job.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/measurement_mapping.h"

namespace oscilab::daq {

/// Reads recordings (each with its sidecar) into the analysis' channels, in the order given.
/// Throws InputError naming the file for a recording that cannot be read.
std::vector<analysis::MeasurementChannels> read_campaign(const std::vector<std::string>& paths,
                                                         const MappingOverrides& overrides);

/// The same, each recording's samples left in its file where its format allows it
/// (streamed_measurement_channels): for an analysis in bounded memory.
std::vector<analysis::MeasurementChannels> open_campaign_streamed(
    const std::vector<std::string>& paths, const MappingOverrides& overrides);

/// Reads recordings (read_campaign) and runs the offline analysis of all of them
/// together: the input stage of analyze, fit and diagnose, in the CLI and the app. Throws
/// InputError naming the file for a recording that cannot be read.
analysis::CampaignAnalysis analyze_recordings(const std::vector<std::string>& paths,
                                              const MappingOverrides& overrides,
                                              const analysis::PipelineSettings& settings,
                                              const ProgressFn& progress = {},
                                              const CancelToken& cancel = {});

}  // namespace oscilab::daq

#include "app/cli/campaign_input.h"

#include "app/cli/progress_bar.h"
#include "daq/recording/recording.h"

namespace oscilab::cli {

analysis::CampaignAnalysis analyze_recordings(const std::vector<std::string>& paths,
                                              const daq::MappingOverrides& overrides,
                                              const analysis::PipelineSettings& settings) {
  std::vector<analysis::MeasurementChannels> records;
  for (const auto& path : paths) {
    records.push_back(daq::measurement_channels(daq::read_recording(path), overrides));
  }
  ProgressBar bar("analyze");
  return analysis::analyze_campaign(records, settings, bar.callback());
}

}  // namespace oscilab::cli

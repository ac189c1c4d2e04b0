#include "daq/recording/campaign_reader.h"

#include "daq/recording/recording.h"

namespace oscilab::daq {

analysis::CampaignAnalysis analyze_recordings(const std::vector<std::string>& paths,
                                              const MappingOverrides& overrides,
                                              const analysis::PipelineSettings& settings,
                                              const ProgressFn& progress,
                                              const CancelToken& cancel) {
  std::vector<analysis::MeasurementChannels> records;
  for (const auto& path : paths)
    records.push_back(measurement_channels(read_recording(path), overrides));
  return analysis::analyze_campaign(records, settings, progress, cancel);
}

}  // namespace oscilab::daq

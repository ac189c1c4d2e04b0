#include "daq/recording/campaign_reader.h"

#include <exception>

#include "analysis/common/parallel_for.h"

#include "daq/recording/recording.h"

namespace oscilab::daq {

namespace {

// One file per thread (decoding dominates); the first error in the order given is rethrown.
template <class Open>
std::vector<analysis::MeasurementChannels> open_each(const std::vector<std::string>& paths,
                                                     const Open& open) {
  std::vector<analysis::MeasurementChannels> records(paths.size());
  std::vector<std::exception_ptr> errors(paths.size());
  parallel_for(paths.size(), 0, [&](std::size_t i) {
    try {
      records[i] = open(paths[i]);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return records;
}

}  // namespace

std::vector<analysis::MeasurementChannels> read_campaign(const std::vector<std::string>& paths,
                                                         const MappingOverrides& overrides) {
  return open_each(paths, [&](const std::string& path) {
    return measurement_channels(read_recording(path), overrides);
  });
}

std::vector<analysis::MeasurementChannels> open_campaign_streamed(
    const std::vector<std::string>& paths, const MappingOverrides& overrides) {
  return open_each(paths, [&](const std::string& path) {
    return streamed_measurement_channels(path, overrides);
  });
}

analysis::CampaignAnalysis analyze_recordings(const std::vector<std::string>& paths,
                                              const MappingOverrides& overrides,
                                              const analysis::PipelineSettings& settings,
                                              const ProgressFn& progress,
                                              const CancelToken& cancel) {
  return analysis::analyze_campaign(read_campaign(paths, overrides), settings, progress, cancel);
}

}  // namespace oscilab::daq

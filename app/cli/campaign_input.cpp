#include "app/cli/campaign_input.h"

#include <chrono>

#include "app/cli/progress_bar.h"
#include "daq/recording/campaign_reader.h"
#include "daq/recording/measurement_mapping.h"

namespace oscilab::cli {

analysis::CampaignAnalysis run_input_stage(const std::vector<std::string>& paths,
                                           const daq::MappingOverrides& overrides,
                                           const analysis::PipelineSettings& settings,
                                           InputTimes* times, const InputStageOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  const Clock::time_point start = Clock::now();
  const std::vector<analysis::MeasurementChannels> records =
      options.streamed ? daq::open_campaign_streamed(paths, overrides)
                       : daq::read_campaign(paths, overrides);
  const Clock::time_point read = Clock::now();
  ProgressBar bar("analyze");
  analysis::CampaignAnalysis campaign =
      analysis::analyze_campaign(records, settings, bar.callback(), {}, options.retention);
  if (times != nullptr) {
    times->read_s = seconds(read - start);
    times->analysis_s = seconds(Clock::now() - read);
    times->signal_s = 0.0;
    for (const auto& r : records) {
      times->signal_s += static_cast<double>(r.sample_count()) / r.sample_rate_hz;
    }
  }
  return campaign;
}

}  // namespace oscilab::cli

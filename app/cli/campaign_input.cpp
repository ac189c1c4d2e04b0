#include "app/cli/campaign_input.h"

#include "app/cli/progress_bar.h"
#include "daq/recording/campaign_reader.h"

namespace oscilab::cli {

analysis::CampaignAnalysis analyze_recordings(const std::vector<std::string>& paths,
                                              const daq::MappingOverrides& overrides,
                                              const analysis::PipelineSettings& settings) {
  ProgressBar bar("analyze");
  return daq::analyze_recordings(paths, overrides, settings, bar.callback());
}

}  // namespace oscilab::cli

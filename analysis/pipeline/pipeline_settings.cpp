#include "analysis/pipeline/pipeline_settings.h"

namespace oscilab::analysis {

nlohmann::json PipelineSettings::to_json() const {
  return {{"harmonics", harmonics},
          {"well_boundary_m", well_boundary_m},
          {"min_steady_cycles", min_steady_cycles},
          {"steady_rel_tol", steady_rel_tol},
          {"level_change_rel", level_change_rel},
          {"integration_highpass_hz", integration_highpass_hz},
          {"derivative_lowpass_hz", derivative_lowpass_hz},
          {"stiffness_velocity_band_rel", stiffness_velocity_band_rel},
          {"stiffness_bins", stiffness_bins},
          {"damping_position_band_rel", damping_position_band_rel},
          {"damping_bins", damping_bins},
          {"edge_trim_s", edge_trim_s}};
}

}  // namespace oscilab::analysis

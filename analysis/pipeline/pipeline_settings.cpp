#include "analysis/pipeline/pipeline_settings.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/common/input_error.h"

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

void PipelineSettings::validate() const {
  const auto refuse = [](const std::string& name, double value, const std::string& rule) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    throw InputError("analysis setting " + name + " = " + text + ": " + rule);
  };
  const auto positive = [&](const std::string& name, double value, const std::string& what) {
    if (!(value > 0) || !std::isfinite(value)) refuse(name, value, "must be a positive " + what);
  };
  if (harmonics < 1) refuse("harmonics", harmonics, "at least 1 harmonic per cycle fit");
  if (!std::isfinite(well_boundary_m)) refuse("well_boundary_m", well_boundary_m, "not finite");
  if (min_steady_cycles < 1) refuse("min_steady_cycles", min_steady_cycles, "at least 1 cycle");
  positive("steady_rel_tol", steady_rel_tol, "relative tolerance");
  positive("level_change_rel", level_change_rel, "relative change");
  positive("integration_highpass_hz", integration_highpass_hz, "frequency");
  positive("derivative_lowpass_hz", derivative_lowpass_hz, "frequency");
  positive("stiffness_velocity_band_rel", stiffness_velocity_band_rel, "share");
  positive("damping_position_band_rel", damping_position_band_rel, "share");
  if (stiffness_bins < 1) refuse("stiffness_bins", stiffness_bins, "at least 1 bin");
  if (damping_bins < 1) refuse("damping_bins", damping_bins, "at least 1 bin");
  if (!(edge_trim_s >= 0) || !std::isfinite(edge_trim_s)) {
    refuse("edge_trim_s", edge_trim_s, "must be 0 or more seconds");
  }
}

}  // namespace oscilab::analysis

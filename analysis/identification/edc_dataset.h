#pragma once

#include <string>
#include <vector>

#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

/// One measured stepped-sine level as an identification uses it (§4.1): S_k^mes and its spread.
struct MeasuredLevel {
  double f0_n = 0.0;
  double edc_j = 0.0;          // S_k^mes: mean over the level's steady cycles
  double edc_std_j = 0.0;      // σ_k^mes over the cycles (the paper's error bars are ±3σ)
  int cycles = 0;              // steady cycles averaged
  double noise_floor_j = 0.0;  // σ of the mean predicted from the sensor noise
  double amplitude_m = 0.0;    // |Z1|, for slopes and plots
  std::string record;          // where it came from
  /// The response's harmonic content over the steady cycles (0 cycles: not measured): the mean
  /// of |Z1| and of the ratios |Z2|/|Z1|, |Z3|/|Z1| with their standard errors (spread over the
  /// cycles / √cycles). Fingerprints of stiffness and damping laws beside the EDC.
  int harmonic_cycles = 0;
  double z1_abs_se_m = 0.0;
  double h2_ratio = 0.0, h2_ratio_se = 0.0;
  double h3_ratio = 0.0, h3_ratio_se = 0.0;
  /// Standard error of S_k^mes: σ/√cycles, not below the sensor-noise floor. 0 for data without
  /// cycles (noise-free twin data).
  double sigma_of_mean_j() const;
};

/// The measured levels of one well at one forcing frequency, in increasing f0: one call of the
/// model's level response (each level on the branch reached by increasing f0 from rest, as the
/// stepped test does).
struct EdcGroup {
  bool positive_well = true;
  double freq_hz = 0.0;
  std::vector<MeasuredLevel> levels;
};

/// What an EDC fit compares the model with: S^mes = vec{S₋^mes, S₊^mes} of §4.1, grouped by well
/// and frequency, and the levels that were left out (cross-well, not period-1, no steady cycles)
/// with the reason.
struct EdcDataset {
  std::vector<EdcGroup> groups;
  std::vector<std::string> excluded;  // "run1.flac: positive well, f0 3.10 N: not-period-1"
  int level_count() const;
  /// The group of this well (the first at any frequency), or nullptr.
  const EdcGroup* group(bool positive_well) const;
};

/// The usable stepped-sine levels of analysed records. Records whose excitation frequencies
/// agree within 0.1 % join one group per well; two levels of one group whose f0 agree within
/// 1e-6 of the largest are merged (cycle-weighted mean). Throws InputError naming the records
/// when none has a usable stepped-sine level.
EdcDataset edc_dataset(const CampaignAnalysis& campaign);

/// Twin data: the model's own EDC at the given levels of each well (no noise, no cycles), for
/// tests and for studies of what a test design can identify. `edc_j[g][k]` belongs to group g.
EdcDataset edc_dataset_from_values(double freq_hz, const std::vector<double>& positive_f0_n,
                                   const std::vector<double>& positive_edc_j,
                                   const std::vector<double>& negative_f0_n,
                                   const std::vector<double>& negative_edc_j);

}  // namespace oscilab::analysis

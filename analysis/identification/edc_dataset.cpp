#include "analysis/identification/edc_dataset.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

// Records at one forcing frequency within this fraction share a group (a DAQ clock is good to
// far better than 0.1 %; stepped tests at different frequencies differ by far more).
constexpr double kSameFrequencyRel = 1e-3;

std::string describe(const std::string& record, const LevelResult& level) {
  std::ostringstream out;
  out.precision(3);
  out << record << ": " << to_string(level.well) << ", f0 " << std::fixed << level.f0_n
      << " N: " << (level.flags().empty() ? "no steady cycles" : level.flags());
  return out.str();
}

void sort_and_merge(EdcGroup& group) {
  auto& levels = group.levels;
  std::sort(levels.begin(), levels.end(),
            [](const MeasuredLevel& a, const MeasuredLevel& b) { return a.f0_n < b.f0_n; });
  if (levels.empty()) return;
  const double tol = 1e-6 * levels.back().f0_n;
  std::vector<MeasuredLevel> merged;
  for (const MeasuredLevel& level : levels) {
    if (merged.empty() || level.f0_n - merged.back().f0_n > tol) {
      merged.push_back(level);
      continue;
    }
    MeasuredLevel& m = merged.back();
    const double wa = std::max(1, m.cycles), wb = std::max(1, level.cycles);
    const double w = wa + wb;
    const double mean = (wa * m.edc_j + wb * level.edc_j) / w;
    // Pooled spread: within-level variances plus the spread of the two means.
    const double var =
        (wa * (m.edc_std_j * m.edc_std_j + (m.edc_j - mean) * (m.edc_j - mean)) +
         wb * (level.edc_std_j * level.edc_std_j + (level.edc_j - mean) * (level.edc_j - mean))) /
        w;
    m.f0_n = (wa * m.f0_n + wb * level.f0_n) / w;
    m.edc_j = mean;
    m.edc_std_j = std::sqrt(var);
    m.amplitude_m = (wa * m.amplitude_m + wb * level.amplitude_m) / w;
    m.noise_floor_j = std::hypot(wa * m.noise_floor_j, wb * level.noise_floor_j) / w;
    m.cycles += level.cycles;
    m.record += "+" + level.record;
  }
  levels = std::move(merged);
}

// The coherent mean of harmonic h over the cycles (phases share one reference time, so the mean
// of the complex amplitudes averages the noise down; a mean of magnitudes would keep the noise's
// positive bias), and the standard error of its magnitude: the scatter per component over √n.
void coherent_mean(const std::vector<std::complex<double>>& v, std::complex<double>& mean,
                   double& se) {
  mean = 0.0;
  for (const auto& x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double ss = 0.0;
  for (const auto& x : v) ss += std::norm(x - mean);
  const double n = static_cast<double>(v.size());
  se = std::sqrt(ss / (2.0 * (n - 1.0)) / n);
}

// |Z1|'s standard error and the ratios |Z2|/|Z1|, |Z3|/|Z1| of the coherent means over the level's
// steady cycles, each ratio's standard error by first-order propagation.
void harmonic_content(const RecordAnalysis& record, const LevelResult& level, MeasuredLevel& m) {
  std::vector<std::complex<double>> z[3];
  for (const CycleFit& c : record.cycles) {
    if (c.start_s < level.start_s - 1e-9 || c.end_s > level.end_s + 1e-9) continue;
    if (c.z_h.size() < 3) continue;
    for (int h = 0; h < 3; ++h) z[h].push_back(c.z_h[static_cast<std::size_t>(h)]);
  }
  if (z[0].size() < 2) return;
  std::complex<double> mean[3];
  double se[3];
  for (int h = 0; h < 3; ++h) coherent_mean(z[h], mean[h], se[h]);
  const double a1 = std::abs(mean[0]);
  if (!(a1 > 0.0)) return;
  m.z1_abs_se_m = se[0];
  m.h2_ratio = std::abs(mean[1]) / a1;
  m.h3_ratio = std::abs(mean[2]) / a1;
  m.h2_ratio_se = std::hypot(se[1], m.h2_ratio * se[0]) / a1;
  m.h3_ratio_se = std::hypot(se[2], m.h3_ratio * se[0]) / a1;
  m.harmonic_cycles = static_cast<int>(z[0].size());
}

EdcGroup& group_for(EdcDataset& data, bool positive, double freq_hz) {
  for (EdcGroup& g : data.groups) {
    if (g.positive_well == positive && std::abs(g.freq_hz - freq_hz) <= kSameFrequencyRel * freq_hz)
      return g;
  }
  data.groups.push_back({positive, freq_hz, {}});
  return data.groups.back();
}

}  // namespace

double MeasuredLevel::sigma_of_mean_j() const {
  const double from_cycles = cycles > 0 ? edc_std_j / std::sqrt(static_cast<double>(cycles)) : 0.0;
  return std::max(from_cycles, noise_floor_j);
}

int EdcDataset::level_count() const {
  int n = 0;
  for (const EdcGroup& g : groups) n += static_cast<int>(g.levels.size());
  return n;
}

const EdcGroup* EdcDataset::group(bool positive_well) const {
  for (const EdcGroup& g : groups) {
    if (g.positive_well == positive_well) return &g;
  }
  return nullptr;
}

EdcDataset edc_dataset(const CampaignAnalysis& campaign) {
  EdcDataset data;
  std::string names;
  for (const RecordAnalysis& record : campaign.records) {
    names += (names.empty() ? "" : ", ") + record.name;
    if (!record.stepped_sine) {
      data.excluded.push_back(record.name + ": not a stepped-sine record (no EDC levels)");
      continue;
    }
    for (const LevelResult& level : record.levels) {
      const bool known_well = level.well == Well::Positive || level.well == Well::Negative;
      if (!level.usable() || !known_well || !(level.edc_mean_j > 0.0)) {
        data.excluded.push_back(describe(record.name, level));
        continue;
      }
      MeasuredLevel m;
      m.f0_n = level.f0_n;
      m.edc_j = level.edc_mean_j;
      m.edc_std_j = level.edc_std_j;
      m.cycles = level.cycles;
      m.noise_floor_j = level.edc_noise_floor_j;
      m.amplitude_m = level.z1_abs_m;
      m.record = record.name;
      harmonic_content(record, level, m);
      group_for(data, level.well == Well::Positive, record.setup.excitation_freq_hz)
          .levels.push_back(m);
    }
  }
  for (EdcGroup& g : data.groups) sort_and_merge(g);
  if (data.level_count() == 0) {
    throw InputError((names.empty() ? std::string("no records") : names) +
                     ": no usable stepped-sine level to fit (every level is cross-well, not "
                     "period-1 or without steady cycles)");
  }
  return data;
}

EdcDataset edc_dataset_from_values(double freq_hz, const std::vector<double>& positive_f0_n,
                                   const std::vector<double>& positive_edc_j,
                                   const std::vector<double>& negative_f0_n,
                                   const std::vector<double>& negative_edc_j) {
  if (positive_f0_n.size() != positive_edc_j.size() ||
      negative_f0_n.size() != negative_edc_j.size()) {
    throw InputError("EDC dataset: each f0 needs one EDC value");
  }
  EdcDataset data;
  const auto add = [&](bool positive, const std::vector<double>& f0, const std::vector<double>& s) {
    if (f0.empty()) return;
    EdcGroup group{positive, freq_hz, {}};
    for (std::size_t k = 0; k < f0.size(); ++k) {
      MeasuredLevel m;
      m.f0_n = f0[k];
      m.edc_j = s[k];
      m.record = "twin";
      group.levels.push_back(m);
    }
    sort_and_merge(group);
    data.groups.push_back(std::move(group));
  };
  add(true, positive_f0_n, positive_edc_j);
  add(false, negative_f0_n, negative_edc_j);
  return data;
}

}  // namespace oscilab::analysis

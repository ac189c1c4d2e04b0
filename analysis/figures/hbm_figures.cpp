#include "analysis/figures/hbm_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "analysis/common/input_error.h"

namespace oscilab::figures {
namespace {

using analysis::Branch;
using analysis::BranchPoint;
using analysis::PointMarker;
using Style = FigureSeries::Style;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kMm = 1e3;  // m → mm
constexpr double kMj = 1e3;  // J → mJ

// z(t = 0) of a point: a0 + Σ a_q (cos 0 = 1), the HBM orbit at the Poincaré phase of the map.
double z_at_period_start(const BranchPoint& p) {
  double z = p.coefficients[0];
  for (Eigen::Index i = 1; i < p.coefficients.size(); i += 2) z += p.coefficients[i];
  return z;
}

// |Z_h| of harmonic h of the forcing frequency (base harmonic ν h of the ansatz).
double harmonic_abs(const Branch& branch, const BranchPoint& p, int h) {
  if (h == 0) return std::abs(p.coefficients[0]);
  const Eigen::Index q = static_cast<Eigen::Index>(branch.hbm.subharmonic) * h;
  if (2 * q >= p.coefficients.size()) return kNan;
  return std::hypot(p.coefficients[2 * q - 1], p.coefficients[2 * q]);
}

// Two series for one quantity along a branch: the stable parts solid, the unstable ones dashed
// (points whose stability is unknown count as stable). Each part shares its end point with the
// next, so the line is unbroken where the style changes.
template <typename Value>
void add_branch_series(FigurePanel& panel, const Branch& branch, const std::string& name, int color,
                       Value value) {
  FigureSeries stable{name + " (stable)", Style::Line, color, {}, {}, 2.0};
  FigureSeries unstable{name + " (unstable)", Style::DashedLine, color, {}, {}, 2.0};
  auto is_stable = [](const BranchPoint& p) { return !p.stability_known || p.floquet.stable; };
  bool any_unstable = false;
  for (std::size_t i = 0; i < branch.points.size(); ++i) {
    const BranchPoint& p = branch.points[i];
    const bool s = is_stable(p);
    any_unstable = any_unstable || !s;
    FigureSeries& own = s ? stable : unstable;
    FigureSeries& other = s ? unstable : stable;
    own.x.push_back(p.f0_n);
    own.y.push_back(value(p));
    if (i + 1 < branch.points.size() && is_stable(branch.points[i + 1]) != s) {
      // Change of stability between i and i + 1: the other style starts at point i.
      other.x.push_back(p.f0_n);
      other.y.push_back(value(p));
    } else {
      other.x.push_back(kNan);
      other.y.push_back(kNan);
    }
  }
  panel.series.push_back(stable);
  if (any_unstable) panel.series.push_back(unstable);
}

template <typename Value>
void add_event_markers(FigurePanel& panel, const Branch& branch, Value value, bool with_names) {
  FigureSeries folds{with_names ? "fold" : "", Style::Markers, 4, {}, {}, 9.0};
  FigureSeries flips{with_names ? "period doubling" : "", Style::Markers, 3, {}, {}, 9.0};
  for (const analysis::BranchEvent& e : branch.events) {
    const BranchPoint& p = branch.points[e.point_index];
    FigureSeries* target = e.kind == PointMarker::Fold             ? &folds
                           : e.kind == PointMarker::PeriodDoubling ? &flips
                                                                   : nullptr;
    if (target == nullptr) continue;
    target->x.push_back(p.f0_n);
    target->y.push_back(value(p));
  }
  if (!folds.x.empty()) panel.series.push_back(folds);
  if (!flips.x.empty()) panel.series.push_back(flips);
}

std::string legend_name(const std::vector<NamedBranch>& branches, std::size_t i,
                        const std::string& single) {
  return branches.size() == 1 ? single : single + ", " + branches[i].name;
}

const char* kF0Label = "forcing amplitude f0 [N]";

}  // namespace

void write_branches_csv(const std::vector<CsvBranch>& branches, bool well_column,
                        bool period_column, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw InputError(path + ": cannot write");
  write_branches_csv(branches, well_column, period_column, file);
  file.close();
  if (!file) throw InputError(path + ": write failed");
}

void write_branches_csv(const std::vector<CsvBranch>& branches, bool well_column,
                        bool period_column, std::ostream& file) {
  if (branches.size() == 1 && !well_column && !period_column) {
    analysis::write_branch_csv(*branches[0].branch, file);
    return;
  }
  for (std::size_t i = 0; i < branches.size(); ++i) {
    std::ostringstream text;
    analysis::write_branch_csv(*branches[i].branch, text);
    std::istringstream lines(text.str());
    std::string line;
    std::getline(lines, line);
    if (i == 0) {
      file << line << (well_column ? ",well" : "") << (period_column ? ",period" : "") << '\n';
    }
    while (std::getline(lines, line)) {
      file << line;
      if (well_column) file << ',' << to_string(branches[i].well);
      if (period_column) file << ',' << branches[i].period;
      file << '\n';
    }
  }
}

Figure branch_figure(const std::string& title, const std::vector<NamedBranch>& branches) {
  Figure figure;
  figure.title = title;
  FigurePanel amp{"", kF0Label, "response amplitude (max z - min z)/2 [mm]", {}, true};
  FigurePanel edc{"", kF0Label, "energy dissipated per cycle [mJ]", {}, true};
  for (std::size_t i = 0; i < branches.size(); ++i) {
    const Branch& b = *branches[i].branch;
    const int color = branches.size() == 1 ? 0 : static_cast<int>(i) + 1;
    const std::string name = legend_name(branches, i, "HBM");
    add_branch_series(amp, b, name, color,
                      [](const BranchPoint& p) { return p.measures.amp_m * kMm; });
    add_branch_series(edc, b, name, color,
                      [](const BranchPoint& p) { return p.measures.edc_j * kMj; });
    add_event_markers(
        amp, b, [](const BranchPoint& p) { return p.measures.amp_m * kMm; }, i == 0);
    add_event_markers(
        edc, b, [](const BranchPoint& p) { return p.measures.edc_j * kMj; }, i == 0);
  }
  figure.panels.push_back(amp);
  figure.panels.push_back(edc);
  if (branches.size() == 1) {
    const Branch& b = *branches[0].branch;
    FigurePanel harmonics{"", kF0Label, "normalised harmonic |Z_h| / |Z_1| [-]", {}, true};
    const int largest = std::min(b.hbm.harmonics, 7);
    int color = 1;
    for (int h = 0; h <= largest; ++h) {
      if (h == 1) continue;
      double peak = 0.0;
      for (const BranchPoint& p : b.points) {
        const double r = harmonic_abs(b, p, h) / harmonic_abs(b, p, 1);
        if (std::isfinite(r)) peak = std::max(peak, r);
      }
      if (peak < 1e-3) continue;  // e.g. the even harmonics of a symmetric system
      char name[32];
      std::snprintf(name, sizeof name, "h = %d", h);
      add_branch_series(harmonics, b, name, color++, [&b, h](const BranchPoint& p) {
        return harmonic_abs(b, p, h) / harmonic_abs(b, p, 1);
      });
    }
    // Only the solid parts carry a name; the dashed twins would double the legend.
    for (FigureSeries& s : harmonics.series) {
      const auto pos = s.name.find(" (");
      if (s.style == Style::DashedLine) s.name.clear();
      if (pos != std::string::npos && !s.name.empty()) s.name.erase(pos);
    }
    figure.panels.push_back(harmonics);
  }
  return figure;
}

Figure sweep_figure(const std::string& title, const Branch& branch,
                    const analysis::AmplitudeSweep& sweep) {
  Figure figure;
  figure.title = title;
  figure.panel_height_px = 520;
  FigurePanel amp{"", kF0Label, "response amplitude (max z - min z)/2 [mm]", {}, true};
  FigureSeries up{"time integration, sweep up", Style::Line, 1, {}, {}, 1.4};
  FigureSeries down{"time integration, sweep down", Style::Line, 2, {}, {}, 1.4};
  for (const analysis::AmplitudeSweepPeriod& p : sweep.periods) {
    FigureSeries& s = p.up ? up : down;
    s.x.push_back(p.f0_n);
    s.y.push_back(p.amp_m * kMm);
  }
  amp.series.push_back(up);
  amp.series.push_back(down);
  add_branch_series(amp, branch, "HBM", 0,
                    [](const BranchPoint& p) { return p.measures.amp_m * kMm; });
  add_event_markers(
      amp, branch, [](const BranchPoint& p) { return p.measures.amp_m * kMm; }, true);
  figure.panels.push_back(amp);
  return figure;
}

Figure map_figure(const std::string& title, const std::vector<NamedBranch>& branches,
                  const analysis::BifurcationMap& map) {
  Figure figure;
  figure.title = title;
  figure.panel_height_px = 400;
  FigurePanel amp{"HBM amplitude", kF0Label, "response amplitude (max z - min z)/2 [mm]", {}, true};
  // One section panel per well (their z ranges are far apart: z+* and z-* sit 50 mm apart).
  for (std::size_t i = 0; i < branches.size(); ++i) {
    const Branch& b = *branches[i].branch;
    const bool positive = b.positive_well;
    FigurePanel section{
        "Poincare section, " + branches[i].name + ": z sampled once per forcing period",
        kF0Label,
        "z at t = nT [mm]",
        {},
        true};
    // The z+* sections fall with f0 and split to both sides at the flip; the z-* ones dip.
    section.legend_corner =
        positive ? FigurePanel::Corner::BottomLeft : FigurePanel::Corner::TopRight;
    FigureSeries dots{
        "time simulation (last sampled periods of each level)", Style::Dots, 1, {}, {}, 4.5};
    for (const analysis::BifurcationMapRow& row : map.rows) {
      if (row.positive_well != positive) continue;
      dots.x.push_back(row.f0_n);
      dots.y.push_back(row.z_m * kMm);
    }
    add_branch_series(section, b, "HBM orbit z(nT)", 0,
                      [](const BranchPoint& p) { return z_at_period_start(p) * kMm; });
    add_event_markers(
        section, b, [](const BranchPoint& p) { return z_at_period_start(p) * kMm; }, true);
    if (!dots.x.empty()) section.series.push_back(dots);
    figure.panels.push_back(section);

    const int color = branches.size() == 1 ? 0 : static_cast<int>(i) + 1;
    add_branch_series(amp, b, legend_name(branches, i, "HBM"), color,
                      [](const BranchPoint& p) { return p.measures.amp_m * kMm; });
    add_event_markers(
        amp, b, [](const BranchPoint& p) { return p.measures.amp_m * kMm; }, i == 0);
  }
  figure.panels.push_back(amp);
  return figure;
}

}  // namespace oscilab::figures

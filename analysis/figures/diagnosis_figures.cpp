#include "analysis/figures/diagnosis_figures.h"

#include <cmath>
#include <string>

namespace oscilab::figures {

using Style = FigureSeries::Style;

Figure residual_figure(const analysis::DiagnosisResult& r) {
  Figure figure;
  figure.title = "EDC residual (S_mes - S_mod) / sigma per level: baseline and final model";
  for (bool positive : {true, false}) {
    FigurePanel panel{positive ? "z+* well" : "z-* well",
                      "forcing amplitude f0 [N]",
                      "residual [sigma]",
                      {},
                      true,
                      FigurePanel::Corner::TopRight};
    FigureSeries before{
        "baseline (" + std::string("paper form") + ")", Style::Markers, 1, {}, {}, 7.0};
    FigureSeries after{"final (" + r.verdict + ")", Style::Markers, 0, {}, {}, 7.0};
    for (const auto& d : r.baseline_maps.levels) {
      if (d.positive_well != positive) continue;
      before.x.push_back(d.f0_n);
      before.y.push_back(d.residual_sigma);
    }
    for (const auto& d : r.final_maps.levels) {
      if (d.positive_well != positive) continue;
      after.x.push_back(d.f0_n);
      after.y.push_back(d.residual_sigma);
    }
    FigureSeries band{"±3 sigma", Style::DashedLine, 5, {}, {}, 1.0};
    if (!before.x.empty()) {
      const double lo = before.x.front(), hi = before.x.back();
      band.x = {lo, hi, std::nan(""), lo, hi};
      band.y = {3.0, 3.0, std::nan(""), -3.0, -3.0};
    }
    panel.series = {before, after, band};
    if (!before.x.empty()) figure.panels.push_back(panel);
  }
  return figure;
}

Figure missing_energy_figure(const analysis::DiagnosisResult& r) {
  Figure figure;
  figure.title = "Energy the baseline misses against the response amplitude (log10-log10)";
  FigurePanel panel{"slope ~1 Coulomb, ~2 viscous, ~3 quadratic damping / presliding, ~4 cubic",
                    "log10 amplitude |Z1| [m]",
                    "log10 |S_mes - S_mod| [J]",
                    {},
                    true,
                    FigurePanel::Corner::TopLeft};
  FigureSeries missing{"S_mes > S_mod", Style::Markers, 1, {}, {}, 7.0};
  FigureSeries excess{"S_mes < S_mod", Style::Markers, 2, {}, {}, 7.0};
  for (const auto& d : r.baseline_maps.levels) {
    const double difference = d.edc_mes_j - d.edc_mod_j;
    if (!(d.amplitude_m > 0.0) || difference == 0.0) continue;
    auto& s = difference > 0.0 ? missing : excess;
    s.x.push_back(std::log10(d.amplitude_m));
    s.y.push_back(std::log10(std::abs(difference)));
  }
  panel.series = {missing, excess};
  figure.panels = {panel};
  figure.panel_height_px = 460;
  return figure;
}

}  // namespace oscilab::figures

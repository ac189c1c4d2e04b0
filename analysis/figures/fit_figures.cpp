#include "analysis/figures/fit_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "analysis/common/input_error.h"
#include "analysis/common/parallel_for.h"
#include "analysis/edc/well.h"
#include "analysis/figures/figure_png.h"
#include "analysis/model/position_dependent_friction.h"

namespace oscilab::figures {
namespace {

using Style = FigureSeries::Style;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kMj = 1e3;  // J → mJ
constexpr double kMm = 1e3;  // m → mm

const char* well_name(bool positive) { return positive ? "z+* well" : "z-* well"; }

struct CsvFile {
  CsvFile(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "w")) {
    if (!file_) throw InputError(path + ": cannot write");
  }
  ~CsvFile() {
    if (file_) std::fclose(file_);
  }
  std::FILE* get() { return file_; }
  void close() {
    const bool failed = std::ferror(file_) != 0;
    const int status = std::fclose(file_);
    file_ = nullptr;
    if (status != 0 || failed) throw InputError(path_ + ": write failed");
  }

 private:
  std::string path_;
  std::FILE* file_;
};

}  // namespace

std::vector<CostSlice> cost_slices(const analysis::EdcObjective& objective,
                                   const Eigen::VectorXd& theta, int points, int threads,
                                   const CancelToken& cancel) {
  const auto& form = objective.form();
  std::vector<CostSlice> slices(form.size());
  struct Job {
    int parameter;
    int point;
    Eigen::VectorXd theta;
  };
  std::vector<Job> jobs;
  for (int i = 0; i < form.size(); ++i) {
    slices[i].parameter = form.parameters()[i].name;
    for (int k = 0; k < points; ++k) {
      // 50 % … 150 % of θ̄_i (k_s: of its excess over 1), as far as the bounds allow.
      const double factor = 0.5 + static_cast<double>(k) / std::max(1, points - 1);
      Eigen::VectorXd t = theta;
      t(i) = slices[i].parameter == "ks" ? 1.0 + factor * (theta(i) - 1.0) : factor * theta(i);
      slices[i].value.push_back(t(i));
      jobs.push_back({i, k, t});
    }
    slices[i].weighted_cost.assign(points, kNan);
    slices[i].cost_j.assign(points, kNan);
  }
  oscilab::parallel_for(jobs.size(), threads, [&](std::size_t j) {
    if (cancel.cancelled()) return;
    const analysis::EdcEvaluation e = objective.evaluate(jobs[j].theta);
    slices[jobs[j].parameter].weighted_cost[jobs[j].point] = e.weighted_cost;
    slices[jobs[j].parameter].cost_j[jobs[j].point] = e.cost_j;
  });
  return slices;
}

FitFigureData fit_figure_data(const analysis::EdcObjective& objective, const Eigen::VectorXd& theta,
                              int threads, const CancelToken& cancel) {
  FitFigureData data;
  data.slices = cost_slices(objective, theta, 21, threads, cancel);
  if (!cancel.cancelled()) {
    data.curves =
        analysis::edc_sensitivity(objective, theta, {0.2, 0.5, 0.7, 1.0, 1.2, 1.5}, threads);
  }
  return data;
}

std::vector<NamedFigure> fit_figures(const analysis::FitResult& fit,
                                     const analysis::EdcObjective& objective,
                                     const FitFigureData& data) {
  std::vector<NamedFigure> figures = {{"edc_fit", edc_fit_figure(fit, objective)},
                                      {"convergence", convergence_figure(fit)},
                                      {"friction", friction_figure(fit, objective)},
                                      {"cost_slices", cost_slice_figure(data.slices)}};
  for (bool positive : {true, false}) {
    if (objective.data().group(positive)) {
      figures.push_back({"sensitivity_" + analysis::to_string(analysis::well_of(positive)),
                         sensitivity_figure(data.curves, positive)});
    }
  }
  return figures;
}

Figure edc_fit_figure(const analysis::FitResult& fit, const analysis::EdcObjective& objective) {
  Figure figure;
  figure.title = "Energy dissipated per cycle: measured and fitted (Fig. 15)";
  FigurePanel edc{"",   "forcing amplitude f0 [N]",  "EDC [mJ]", {},
                  true, FigurePanel::Corner::TopLeft};
  FigurePanel deviation{"",   "forcing amplitude f0 [N]",   "(S_mod - S_mes) / S_mes [%]", {},
                        true, FigurePanel::Corner::TopRight};
  const auto& groups = objective.data().groups;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto& group = groups[g];
    const int color = group.positive_well ? 0 : 1;
    const std::string name = well_name(group.positive_well);
    FigureSeries measured{name + " measured", Style::Markers, color, {}, {}, 6.0};
    FigureSeries bars{name + " ±3σ", Style::Line, color, {}, {}, 1.0};
    FigureSeries model{name + " model", Style::DashedLine, color, {}, {}, 2.0};
    FigureSeries dev{name, Style::Line, color, {}, {}, 1.5};
    for (std::size_t i = 0; i < group.levels.size(); ++i) {
      const auto& m = group.levels[i];
      const double mod = fit.evaluation.edc_mod_j[g][i];
      measured.x.push_back(m.f0_n);
      measured.y.push_back(kMj * m.edc_j);
      bars.x.insert(bars.x.end(), {m.f0_n, m.f0_n, kNan});
      bars.y.insert(bars.y.end(),
                    {kMj * (m.edc_j - 3 * m.edc_std_j), kMj * (m.edc_j + 3 * m.edc_std_j), kNan});
      model.x.push_back(m.f0_n);
      model.y.push_back(kMj * mod);
      dev.x.push_back(m.f0_n);
      dev.y.push_back(100.0 * (mod - m.edc_j) / m.edc_j);
    }
    edc.series.push_back(measured);
    edc.series.push_back(bars);
    edc.series.push_back(model);
    deviation.series.push_back(dev);
  }
  figure.panels = {edc, deviation};
  return figure;
}

Figure convergence_figure(const analysis::FitResult& fit) {
  Figure figure;
  figure.title = "Best cost against model evaluations (method " +
                 analysis::fit_method_name(fit.method) + ", Fig. 14)";
  FigurePanel panel{"",    "model evaluations",          "log10 of the best chi2", {},
                    false, FigurePanel::Corner::TopRight};
  FigureSeries s{"best chi2", Style::Line, 0, {}, {}, 2.0};
  for (const auto& [evaluations, cost] : fit.history) {
    s.x.push_back(static_cast<double>(evaluations));
    s.y.push_back(std::log10(std::max(cost, 1e-300)));
  }
  panel.series.push_back(s);
  figure.panels = {panel};
  figure.panel_height_px = 420;
  return figure;
}

Figure friction_figure(const analysis::FitResult& fit, const analysis::EdcObjective& objective) {
  Figure figure;
  figure.title = "Dynamic friction f_d(z) of eq. (6), fitted";
  FigurePanel panel{"", "z [mm]", "f_d [N]", {}, true, FigurePanel::Corner::TopLeft};
  const analysis::Model model = objective.form().build(fit.theta);
  const double z_minus = model.well(false).z_m, z_plus = model.well(true).z_m;
  const double span = z_plus - z_minus;
  for (const auto& term : model.terms()) {
    const auto* friction = dynamic_cast<const analysis::PositionDependentFriction*>(term.get());
    if (!friction) continue;
    FigureSeries curve{"f_d(z)", Style::Line, 0, {}, {}, 2.0};
    for (int k = 0; k <= 200; ++k) {
      const double z = z_minus - 0.3 * span + 1.6 * span * k / 200.0;
      curve.x.push_back(kMm * z);
      curve.y.push_back(friction->dynamic_friction_n(z));
    }
    FigureSeries points{"f_d(z-*), f_d(0), f_d(z+*)", Style::Markers, 1, {}, {}, 9.0};
    for (double z : {z_minus, 0.0, z_plus}) {
      points.x.push_back(kMm * z);
      points.y.push_back(friction->dynamic_friction_n(z));
    }
    panel.series = {curve, points};
  }
  figure.panels = {panel};
  figure.panel_height_px = 420;
  return figure;
}

Figure cost_slice_figure(const std::vector<CostSlice>& slices) {
  Figure figure;
  figure.title = "Cost along each parameter through the optimum (Fig. 13)";
  for (std::size_t i = 0; i < slices.size(); ++i) {
    FigurePanel panel{"",    slices[i].parameter,          "log10 chi2", {},
                      false, FigurePanel::Corner::TopRight};
    FigureSeries s{"", Style::Line, static_cast<int>(i % 6), {}, {}, 2.0};
    for (std::size_t k = 0; k < slices[i].value.size(); ++k) {
      s.x.push_back(slices[i].value[k]);
      s.y.push_back(std::log10(std::max(slices[i].weighted_cost[k], 1e-300)));
    }
    panel.series.push_back(s);
    figure.panels.push_back(panel);
  }
  figure.panel_height_px = 220;
  return figure;
}

Figure sensitivity_figure(const std::vector<analysis::SensitivityCurve>& curves,
                          bool positive_well) {
  Figure figure;
  figure.title = std::string("Sensitivity of the EDC, ") + well_name(positive_well) +
                 " (Fig. 16): each parameter at 20, 50, 70, 120, 150 %";
  std::vector<std::string> parameters;
  for (const auto& c : curves) {
    if (std::find(parameters.begin(), parameters.end(), c.parameter) == parameters.end())
      parameters.push_back(c.parameter);
  }
  for (const std::string& p : parameters) {
    FigurePanel panel{p == "kd"   ? "k_d (all f_d values)"
                      : p == "ks" ? "k_s (static excess k_s - 1)"
                                  : p,
                      "forcing amplitude f0 [N]",
                      "EDC [mJ]",
                      {},
                      true,
                      FigurePanel::Corner::TopLeft};
    int color = 0;
    for (const auto& c : curves) {
      if (c.parameter != p || c.positive_well != positive_well) continue;
      char label[32];
      std::snprintf(label, sizeof label, "%.0f %%", 100.0 * c.factor);
      const bool reference = std::abs(c.factor - 1.0) < 1e-12;
      FigureSeries s{label,
                     reference ? Style::DashedLine : Style::Line,
                     reference ? 5 : color++ % 5,
                     {},
                     {},
                     reference ? 2.5 : 1.5};
      for (std::size_t k = 0; k < c.f0_n.size(); ++k) {
        s.x.push_back(c.f0_n[k]);
        s.y.push_back(c.edc_j[k] != 0.0 ? kMj * c.edc_j[k] : kNan);
      }
      panel.series.push_back(s);
    }
    figure.panels.push_back(panel);
  }
  figure.panel_height_px = 300;
  return figure;
}

void write_fit_tables(const std::string& dir, const analysis::FitResult& fit,
                      const analysis::EdcObjective& objective, const std::vector<CostSlice>& slices,
                      const std::vector<analysis::SensitivityCurve>& curves) {
  {
    CsvFile out(dir + "/edc_fit.csv");
    std::fprintf(out.get(), "well,f0_n,edc_mes_j,edc_std_j,cycles,edc_mod_j,deviation_pct\n");
    const auto& groups = objective.data().groups;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      for (std::size_t i = 0; i < groups[g].levels.size(); ++i) {
        const auto& m = groups[g].levels[i];
        const double mod = fit.evaluation.edc_mod_j[g][i];
        std::fprintf(out.get(), "%s,%.6g,%.9g,%.6g,%d,%.9g,%.4f\n",
                     analysis::to_string(analysis::well_of(groups[g].positive_well)).c_str(),
                     m.f0_n, m.edc_j, m.edc_std_j, m.cycles, mod,
                     100.0 * (mod - m.edc_j) / m.edc_j);
      }
    }
    out.close();
  }
  {
    CsvFile out(dir + "/convergence.csv");
    std::fprintf(out.get(), "evaluations,best_weighted_cost\n");
    for (const auto& [evaluations, cost] : fit.history) {
      std::fprintf(out.get(), "%ld,%.9g\n", evaluations, cost);
    }
    out.close();
  }
  {
    CsvFile out(dir + "/friction.csv");
    std::fprintf(out.get(), "z_m,fd_n\n");
    const Figure f = friction_figure(fit, objective);
    if (!f.panels.front().series.empty()) {
      const auto& curve = f.panels.front().series.front();
      for (std::size_t k = 0; k < curve.x.size(); ++k) {
        std::fprintf(out.get(), "%.9g,%.9g\n", curve.x[k] / kMm, curve.y[k]);
      }
    }
    out.close();
  }
  {
    CsvFile out(dir + "/cost_slices.csv");
    std::fprintf(out.get(), "parameter,value,weighted_cost,cost_j\n");
    for (const auto& s : slices) {
      for (std::size_t k = 0; k < s.value.size(); ++k) {
        std::fprintf(out.get(), "%s,%.9g,%.9g,%.9g\n", s.parameter.c_str(), s.value[k],
                     s.weighted_cost[k], s.cost_j[k]);
      }
    }
    out.close();
  }
  {
    CsvFile out(dir + "/sensitivity.csv");
    std::fprintf(out.get(), "parameter,factor,well,f0_n,edc_j\n");
    for (const auto& c : curves) {
      for (std::size_t k = 0; k < c.f0_n.size(); ++k) {
        std::fprintf(out.get(), "%s,%.3g,%s,%.6g,%.9g\n", c.parameter.c_str(), c.factor,
                     analysis::to_string(analysis::well_of(c.positive_well)).c_str(), c.f0_n[k],
                     c.edc_j[k]);
      }
    }
    out.close();
  }
}

int write_fit_figures(const std::string& dir, const analysis::FitResult& fit,
                      const analysis::EdcObjective& objective, const FitFigureData& data,
                      bool png) {
  write_fit_tables(dir, fit, objective, data.slices, data.curves);
  if (!png) return 0;
  int written = 0;
  for (const NamedFigure& figure : fit_figures(fit, objective, data)) {
    write_figure_png(figure.figure, dir + "/" + figure.stem + ".png");
    ++written;
  }
  return written;
}

}  // namespace oscilab::figures

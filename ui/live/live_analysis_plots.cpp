#include "ui/live/live_analysis_plots.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <QSplitter>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/rfs/cycle_loop.h"
#include "analysis/signal/amplitude_spectrum.h"
#include "ui/live/live_edc_plot_data.h"
#include "ui/plots/plot_helpers.h"
#include "ui/plots/well_colours.h"

namespace oscilab::ui {
namespace {

// Seconds of history the spectrum and the loop look at: the derived z lags the stream by the
// acquisition's derived_latency_s (2 s), so 6 s hold about 4 s of z (36 cycles at 9 Hz).
constexpr double kAnalysisSpanS = 6.0;
// At most this much history is read at once for the restoring-force slices (a first read after
// a long run, or after the slices were reset).
constexpr double kMaxSliceCatchUpS = 60.0;
constexpr int kSliceMaxPoints = 6000;  // per slice: enough for the cloud, quick to draw
const QColor kOtherWell = well_colour(analysis::Well::CrossWell);

QCustomPlot* make_plot(const QString& name, const QString& title, const QString& x_label,
                       const QString& y_label) {
  auto* plot = new QCustomPlot;
  plot->setObjectName(name);
  plot->setMinimumSize(150, 130);  // five plots beside the traces on a 1366-wide screen
  add_plot_title(plot, title)->setMargins(QMargins(0, 2, 0, 0));
  frame_axes(plot, x_label, y_label);
  QFont legend_font = plot->font();
  legend_font.setPointSizeF(legend_font.pointSizeF() * 0.85);
  plot->legend->setFont(legend_font);
  plot->legend->setBrush(QColor(255, 255, 255, 210));
  return plot;
}

// Lists `plottable` in its plot's legend only while it has something to show.
void show_in_legend(QCPAbstractPlottable* plottable, bool show) {
  QCPLegend* legend = plottable->parentPlot()->legend;
  if (show && !legend->hasItemWithPlottable(plottable)) plottable->addToLegend();
  if (!show && legend->hasItemWithPlottable(plottable)) plottable->removeFromLegend();
}

QCPGraph* scatter_graph(QCustomPlot* plot, const QColor& colour, const QString& name) {
  QCPGraph* graph = plot->addGraph();
  graph->setLineStyle(QCPGraph::lsNone);
  graph->setScatterStyle(disc_markers(colour, 3));
  graph->setPen(QPen(colour));
  graph->setName(name);
  graph->setAdaptiveSampling(true);
  return graph;
}

// Range of the finite values of `v` (lo > hi when there are none) and their largest |value|.
void finite_range(const std::vector<double>& v, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (double x : v) {
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  }
}

}  // namespace

LiveAnalysisPlots::LiveAnalysisPlots(QWidget* parent) : QWidget(parent) {
  setObjectName("live_analysis_plots");
  analysis::StreamingSlices::Options slices;
  slices.max_points = kSliceMaxPoints;
  slices_ = analysis::StreamingSlices(slices);

  // EDC against f0 (Fig. 10, with the model as Fig. 15).
  edc_plot_ = make_plot("edc_plot", tr("Energy dissipated per cycle, level by level (Fig. 10)"),
                        tr("forcing amplitude f\u2080 [N]"), tr("EDC [mJ]"));
  edc_plot_->setMinimumHeight(170);
  edc_plot_->legend->setVisible(true);
  edc_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
  const QString well_names[3] = {tr("z\u208a* measured \u00b13\u03c3"),
                                 tr("z\u208b* measured \u00b13\u03c3"), tr("cross-well / unknown")};
  const QColor well_colours[3] = {well_colour(analysis::Well::Positive),
                                  well_colour(analysis::Well::Negative), kOtherWell};
  for (int w = 0; w < 2; ++w) {
    model_graphs_[w] = edc_plot_->addGraph();
    model_graphs_[w]->setPen(QPen(well_colours[w], 1.5, Qt::DashDotLine));
    model_graphs_[w]->removeFromLegend();  // until drawn (named by set_model_label)
  }
  for (int w = 0; w < 3; ++w) {
    QCPGraph* graph = edc_plot_->addGraph();
    graph->setName(well_names[w]);
    graph->setLineStyle(QCPGraph::lsNone);
    graph->setPen(QPen(well_colours[w], 1.5));
    graph->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, well_colours[w],
                                           well_colours[w].lighter(170), 6));
    auto* bars = new QCPErrorBars(edc_plot_->xAxis, edc_plot_->yAxis);
    bars->removeFromLegend();
    bars->setDataPlottable(graph);
    bars->setPen(QPen(well_colours[w], 1.0));
    bars->setWhiskerWidth(5);
    edc_graphs_[w] = graph;
    edc_bars_[w] = bars;
  }
  for (QCPGraph* graph : edc_graphs_) graph->removeFromLegend();  // listed once they have points
  current_graph_ = edc_plot_->addGraph();
  current_graph_->setName(tr("level being filled"));
  current_graph_->setLineStyle(QCPGraph::lsNone);
  current_graph_->setPen(QPen(Qt::black, 1.5));
  current_graph_->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssDiamond, 9));
  current_graph_->removeFromLegend();
  auto* current_bars = new QCPErrorBars(edc_plot_->xAxis, edc_plot_->yAxis);
  current_bars->removeFromLegend();
  current_bars->setDataPlottable(current_graph_);
  current_bars->setPen(QPen(Qt::black, 1.0, Qt::DotLine));
  edc_bars_[3] = current_bars;
  edc_plot_->xAxis->setRange(0.0, 2.8);
  edc_plot_->yAxis->setRange(0.0, 1.0);
  set_plot_hint(edc_plot_, tr("Levels appear here as the stepped sine runs."));

  // The loop of the current cycle (Fig. 9).
  loop_plot_ = make_plot("loop_plot", tr("f\u2013z loop of the current cycle (Fig. 9)"),
                         tr("z [mm]"), tr("f [N]"));
  auto* loop = new QCPCurve(loop_plot_->xAxis, loop_plot_->yAxis);
  loop->setPen(QPen(well_colour(analysis::Well::Positive), 1.5));
  loop->setName(tr("current cycle"));
  set_plot_hint(loop_plot_, tr("Needs a whole cycle of z (2 s behind)."));

  // Spectrum of z.
  spectrum_plot_ = make_plot("spectrum_plot", tr("Spectrum of z, last seconds"),
                             tr("frequency [Hz]"), tr("|Z| [m]"));
  spectrum_plot_->yAxis->setScaleType(QCPAxis::stLogarithmic);
  auto log_ticker = QSharedPointer<QCPAxisTickerLog>::create();
  log_ticker->setSubTickCount(0);
  spectrum_plot_->yAxis->setTicker(log_ticker);
  spectrum_plot_->yAxis->setNumberFormat("eb");
  spectrum_plot_->yAxis->setNumberPrecision(0);
  QCPGraph* spectrum = spectrum_plot_->addGraph();
  spectrum->setPen(QPen(QColor(20, 20, 20), 1.0));
  spectrum->setName(tr("|Z(f)| (Hann)"));
  QCPGraph* harmonics = spectrum_plot_->addGraph();
  harmonics->setLineStyle(QCPGraph::lsImpulse);
  harmonics->setPen(QPen(QColor(213, 94, 0, 120), 5));
  harmonics->setScatterStyle(
      QCPScatterStyle(QCPScatterStyle::ssCircle, QColor(213, 94, 0), Qt::white, 6));
  harmonics->setName(tr("harmonics h\u03bd"));
  spectrum_plot_->legend->setVisible(true);
  spectrum_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignRight);
  spectrum_plot_->xAxis->setRange(0.0, 80.0);
  spectrum_plot_->yAxis->setRange(1e-8, 1e-2);
  set_plot_hint(spectrum_plot_, tr("Needs a few seconds of z."));

  // The restoring force slices (§3.1–3.2, Fig. 7b, 7c).
  stiffness_plot_ =
      make_plot("stiffness_plot", tr("Stiffness slice: R at small |\u017c| (Fig. 7b)"),
                tr("z [mm]"), tr("R [N]"));
  damping_plot_ =
      make_plot("damping_plot", tr("Damping slice: R near the current z\u0304 (Fig. 7c)"),
                tr("\u017c [mm/s]"), tr("R [N]"));
  for (QCustomPlot* plot : {stiffness_plot_, damping_plot_}) {
    scatter_graph(plot, well_colour(analysis::Well::Positive), tr("z\u208a* well"))
        ->removeFromLegend();
    scatter_graph(plot, well_colour(analysis::Well::Negative), tr("z\u208b* well"))
        ->removeFromLegend();
    plot->legend->setVisible(true);
    plot->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
    set_plot_hint(plot, tr("Grows as cycles arrive (R, z, \u017c are 2 s behind)."));
  }

  // EDC on top, loop and spectrum, then the slices.
  auto* middle = new QSplitter(Qt::Horizontal);
  middle->addWidget(loop_plot_);
  middle->addWidget(spectrum_plot_);
  auto* bottom = new QSplitter(Qt::Horizontal);
  bottom->addWidget(stiffness_plot_);
  bottom->addWidget(damping_plot_);
  auto* splitter = new QSplitter(Qt::Vertical);
  splitter->addWidget(edc_plot_);
  splitter->addWidget(middle);
  splitter->addWidget(bottom);
  splitter->setChildrenCollapsible(false);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(splitter);
}

void LiveAnalysisPlots::reset(double frequency_hz) {
  analysis::StreamingSlices::Options slices = slices_.options();
  slices.frequency_hz = frequency_hz;
  slices_ = analysis::StreamingSlices(slices);
  levels_shown_ = static_cast<std::size_t>(-1);
  current_shown_.reset();
  for (QCustomPlot* plot : {stiffness_plot_, damping_plot_, spectrum_plot_}) {
    for (int g = 0; g < plot->graphCount(); ++g) plot->graph(g)->data()->clear();
  }
  if (auto* loop = qobject_cast<QCPCurve*>(loop_plot_->plottable(0))) loop->data()->clear();
}

QCPGraph* LiveAnalysisPlots::edc_graph(analysis::Well well) const {
  return well == analysis::Well::Positive   ? edc_graphs_[0]
         : well == analysis::Well::Negative ? edc_graphs_[1]
                                            : edc_graphs_[2];
}

void LiveAnalysisPlots::set_model_label(const QString& label) {
  for (int w = 0; w < 2; ++w) {
    model_graphs_[w]->setName((w == 0 ? tr("z\u208a* ") : tr("z\u208b* ")) + label + tr(", HBM"));
    model_graphs_[w]->data()->clear();
  }
}

void LiveAnalysisPlots::show_model_edc(const analysis::LevelResponse& positive,
                                       const analysis::LevelResponse& negative) {
  for (int w = 0; w < 2; ++w) {
    const analysis::LevelResponse& r = w == 0 ? positive : negative;
    QVector<double> f0, edc;
    for (std::size_t i = 0; i < r.f0_n.size() && i < r.edc_j.size(); ++i) {
      f0.push_back(r.f0_n[i]);
      edc.push_back(1e3 * r.edc_j[i]);
    }
    model_graphs_[w]->setData(f0, edc, true);
    show_in_legend(model_graphs_[w], !f0.isEmpty());
  }
  levels_shown_ = static_cast<std::size_t>(-1);  // redraw the EDC plot with the model
}

void LiveAnalysisPlots::refresh_slices(const daq::Acquisition& acquisition, double frequency_hz) {
  const daq::AcquisitionStatus status = acquisition.status();
  if (!status.layout_known || !(status.sample_rate_hz > 0)) return;
  const double rate_hz = status.sample_rate_hz;
  const double nu = frequency_hz;
  if (nu > 0 && std::abs(nu - slices_.options().frequency_hz) > 1e-9) {
    analysis::StreamingSlices::Options o = slices_.options();
    o.frequency_hz = nu;
    slices_ = analysis::StreamingSlices(o);  // a new ν: a new cycle length for the bands
  }
  // Samples one by one over what the slices have not taken yet (the derived traces lag).
  const double now_s = status.stream_time_s;
  const double from_s = std::max(
      {0.0, now_s - kMaxSliceCatchUpS, std::min(slices_.taken_until_s(), now_s - kAnalysisSpanS)});
  const int samples = static_cast<int>(std::ceil((now_s - from_s) * rate_hz)) + 2;
  acquisition.history(from_s, now_s, samples, raw_);
  if (raw_.t_s.empty() ||
      slices_.add(raw_.t_s, raw_.z_m, raw_.z_dot_m_s, raw_.restoring_force_n, rate_hz) == 0)
    return;
  for (auto [plot, points] : {std::pair{stiffness_plot_, &slices_.stiffness()},
                              std::pair{damping_plot_, &slices_.damping()}}) {
    QVector<QCPGraphData> wells[2];
    for (const analysis::WellPoint& p : *points) {
      wells[p.positive ? 0 : 1].push_back(QCPGraphData(1e3 * p.x, p.y));  // z in mm, ż in mm/s
    }
    double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
    for (int w = 0; w < 2; ++w) {
      plot->graph(w)->data()->set(wells[w], false);
      show_in_legend(plot->graph(w), !wells[w].isEmpty());
      for (const QCPGraphData& d : wells[w]) {
        x_lo = std::min(x_lo, d.key), x_hi = std::max(x_hi, d.key);
        y_lo = std::min(y_lo, d.value), y_hi = std::max(y_hi, d.value);
      }
    }
    fit_axis(plot->xAxis, x_lo, x_hi, WhenEmpty::Keep);
    fit_axis(plot->yAxis, y_lo, y_hi, WhenEmpty::Keep);
    set_plot_hint(plot, points->empty() ? tr("No samples in the band yet.") : QString());
    plot->replot(QCustomPlot::rpQueuedReplot);
  }
}

void LiveAnalysisPlots::refresh_cycle(const daq::Acquisition& acquisition, double frequency_hz) {
  const daq::AcquisitionStatus status = acquisition.status();
  if (!status.layout_known || !(status.sample_rate_hz > 0)) return;
  const double rate_hz = status.sample_rate_hz;
  const double nu = frequency_hz;
  const double now_s = status.stream_time_s;
  const double from_s = std::max(0.0, now_s - kAnalysisSpanS);
  acquisition.history(from_s, now_s, static_cast<int>(std::ceil((now_s - from_s) * rate_hz)) + 2,
                      raw_);
  if (raw_.t_s.empty()) return;

  // The loop of the newest whole cycle of z.
  if (nu > 0) {
    const analysis::CycleLoop cycle =
        analysis::newest_cycle_loop(raw_.t_s, raw_.z_m, raw_.force_n, nu);
    if (auto* curve = qobject_cast<QCPCurve*>(loop_plot_->plottable(0));
        curve && !cycle.z_m.empty()) {
      QVector<QCPCurveData> data(static_cast<qsizetype>(cycle.z_m.size()));
      for (std::size_t i = 0; i < cycle.z_m.size(); ++i) {
        data[qsizetype(i)] = QCPCurveData(double(i), 1e3 * cycle.z_m[i], cycle.f_n[i]);
      }
      curve->data()->set(data, true);
      const QColor colour = well_colour(analysis::well_of(cycle.positive));
      curve->setPen(QPen(colour, 1.5));
      curve->setBrush(QColor(colour.red(), colour.green(), colour.blue(), 40));
      curve->setName(
          tr("t = %1 \u2013 %2 s").arg(cycle.start_s, 0, 'f', 2).arg(cycle.end_s, 0, 'f', 2));
      double lo = 0, hi = 0;
      finite_range(cycle.z_m, lo, hi);
      fit_axis(loop_plot_->xAxis, 1e3 * lo, 1e3 * hi, WhenEmpty::Keep);
      finite_range(cycle.f_n, lo, hi);
      fit_axis(loop_plot_->yAxis, lo, hi, WhenEmpty::Keep);
      set_plot_hint(loop_plot_, QString());
      loop_plot_->replot(QCustomPlot::rpQueuedReplot);
    }
  }

  // The spectrum of z over the newest few seconds.
  const analysis::ZSpectrum spectrum = analysis::z_spectrum(raw_.z_m, rate_hz, nu);
  if (!spectrum.freq_hz.empty()) {
    QVector<QCPGraphData> data;
    data.reserve(static_cast<qsizetype>(spectrum.freq_hz.size()));
    double peak = 0.0;
    for (std::size_t k = 1; k < spectrum.freq_hz.size(); ++k) {  // the mean removed: from bin 1
      data.push_back(QCPGraphData(spectrum.freq_hz[k], std::max(spectrum.amplitude_m[k], 1e-12)));
      peak = std::max(peak, spectrum.amplitude_m[k]);
    }
    spectrum_plot_->graph(0)->data()->set(data, true);
    QVector<QCPGraphData> markers;
    for (std::size_t h = 0; h < spectrum.harmonic_freq_hz.size(); ++h) {
      markers.push_back(QCPGraphData(spectrum.harmonic_freq_hz[h],
                                     std::max(spectrum.harmonic_amplitude_m[h], 1e-12)));
    }
    spectrum_plot_->graph(1)->data()->set(markers, true);
    spectrum_plot_->graph(1)->setName(tr("h\u03bd, \u03bd = %1 Hz").arg(nu, 0, 'g', 4));
    spectrum_plot_->xAxis->setRange(0.0, std::min(0.5 * rate_hz, nu > 0 ? 9.5 * nu : 60.0));
    if (peak > 0) spectrum_plot_->yAxis->setRange(peak * 1e-5, peak * 3.0);
    set_plot_hint(spectrum_plot_, QString());
    spectrum_plot_->replot(QCustomPlot::rpQueuedReplot);
  }
}

void LiveAnalysisPlots::show_edc(const std::vector<analysis::LevelResult>& levels,
                                 const std::optional<analysis::LevelResult>& current) {
  const bool same_current = current.has_value() == current_shown_.has_value() &&
                            (!current || (current->cycles == current_shown_->cycles &&
                                          current->edc_mean_j == current_shown_->edc_mean_j));
  if (levels.size() == levels_shown_ && same_current) return;
  levels_shown_ = levels.size();
  current_shown_ = current;

  const EdcPlotData data = edc_plot_data(levels, current);
  const std::vector<EdcPoint>* series[3] = {&data.positive, &data.negative, &data.other};
  double top = 0.0;
  for (int w = 0; w < 3; ++w) {
    QVector<double> f0, edc, error;
    for (const EdcPoint& p : *series[w]) {
      f0.push_back(p.f0_n);
      edc.push_back(1e3 * p.edc_j);
      error.push_back(1e3 * p.error_j);
      top = std::max(top, 1e3 * (p.edc_j + p.error_j));
    }
    edc_graphs_[w]->setData(f0, edc, true);
    edc_bars_[w]->setData(error);
    show_in_legend(edc_graphs_[w], !f0.isEmpty());
  }
  QVector<double> f0, edc, error;
  if (data.current) {
    f0.push_back(data.current->f0_n);
    edc.push_back(1e3 * data.current->edc_j);
    error.push_back(1e3 * data.current->error_j);
    top = std::max(top, 1e3 * (data.current->edc_j + data.current->error_j));
    const QColor colour = well_colour(data.current_well);
    current_graph_->setPen(QPen(colour.darker(140), 1.5));
  }
  current_graph_->setData(f0, edc, true);
  edc_bars_[3]->setData(error);
  show_in_legend(current_graph_, !f0.isEmpty());
  // The axes hold the measured points and the model up to a little past the levels measured
  // (the whole model before there are any), so that the first levels are not squeezed flat.
  const double x_top = std::max(2.8, data.max_f0_n + 0.1);
  const double model_top = data.max_f0_n > 0 ? 1.25 * data.max_f0_n + 0.1 : x_top;
  for (QCPGraph* model : model_graphs_) {
    for (auto it = model->data()->constBegin(); it != model->data()->constEnd(); ++it) {
      if (it->key <= model_top) top = std::max(top, it->value);
    }
  }
  edc_plot_->xAxis->setRange(0.0, x_top);
  edc_plot_->yAxis->setRange(0.0, top > 0 ? 1.08 * top : 1.0);
  set_plot_hint(edc_plot_, levels.empty() && !data.current
                               ? tr("Levels appear here as the stepped sine runs.")
                               : QString());
  edc_plot_->replot(QCustomPlot::rpQueuedReplot);
}
}  // namespace oscilab::ui

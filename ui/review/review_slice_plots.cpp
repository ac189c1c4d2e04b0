#include "ui/review/review_slice_plots.h"

#include <algorithm>
#include <vector>

#include <QLabel>
#include <QSplitter>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/pipeline/result_units.h"
#include "ui/plots/plot_helpers.h"
#include "ui/qt_text.h"
#include "ui/review/review_plot_style.h"

namespace oscilab::ui {
namespace {

// Points of the fitted K(z) curve.
constexpr int kCurvePoints = 200;
// Damping slices: green around z₋*, yellow-orange around z₊* (Fig. 7c; Okabe–Ito colours).
const QColor kSliceColour[2] = {QColor(0, 158, 115), QColor(230, 159, 0)};
const QColor kSampleColour(86, 180, 233);  // stiffness-slice samples: light blue (Fig. 7b)
const QColor kFitColour(200, 0, 0);        // the fitted K(z): red (Fig. 7b)

}  // namespace

ReviewSlicePlots::ReviewSlicePlots() {
  // Stiffness slice and damping slices side by side, the fit below.
  stiffness_plot_ = make_review_plot(tr("z [mm]"), tr("R [N]"));
  stiffness_plot_->setObjectName("stiffness_plot");
  add_plot_title(stiffness_plot_, tr("Stiffness slice: R at small |\u017c| (\u00a73.1, Fig. 7b)"));
  stiffness_plot_->legend->setVisible(true);
  stiffness_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
  damping_plot_ = make_review_plot(tr("\u017c [mm/s]"), tr("D = R \u2212 K(z) [N]"));
  damping_plot_->setObjectName("damping_plot");
  add_plot_title(
      damping_plot_,
      tr("Damping slices at the stable equilibria: |z \u2212 z\u0304| < \u03b5_d (Fig. 7c)"));
  damping_plot_->legend->setVisible(true);
  damping_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
  stiffness_label_ = new QLabel;
  stiffness_label_->setObjectName("stiffness_fit");
  stiffness_label_->setWordWrap(true);
  stiffness_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  stiffness_label_->setContentsMargins(6, 2, 6, 4);
  auto* slices = new QSplitter(Qt::Horizontal);
  slices->addWidget(stiffness_plot_);
  slices->addWidget(damping_plot_);
  slices->setChildrenCollapsible(false);
  page_ = new QWidget;
  auto* layout = new QVBoxLayout(page_);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addWidget(slices, 1);
  layout->addWidget(stiffness_label_);
}

QString ReviewSlicePlots::force_unit(const ReviewAnalysis* review, const DisplayUnit& unit) {
  const analysis::MassBasis basis =
      review ? analysis::mass_basis(review->campaign) : analysis::MassBasis::Absolute;
  return qtext(analysis::result_unit(unit.symbol, basis));
}

void ReviewSlicePlots::show(const ReviewAnalysis* review, bool running) {
  stiffness_plot_->clearPlottables();
  damping_plot_->clearPlottables();
  stiffness_label_->clear();
  const analysis::CampaignAnalysis* campaign = review ? &review->campaign : nullptr;
  if (!campaign || !campaign->stiffness) {
    const QString why = !review ? (running ? tr("Analysing\u2026") : tr("No analysis yet"))
                                : tr("No restoring force: %1").arg(qtext(campaign->rfs_message));
    set_plot_hint(stiffness_plot_, why);
    set_plot_hint(damping_plot_, why);
    stiffness_plot_->replot(QCustomPlot::rpQueuedReplot);
    damping_plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  set_plot_hint(stiffness_plot_, {});
  const analysis::StiffnessSlice& slice = *campaign->stiffness;

  // Stiffness slice: the samples, their bin means and the fitted cubic.
  const ScatterPoints& samples = review->slice_points.stiffness;
  std::vector<double> bin_z, bin_r;
  for (const analysis::SliceBin& bin : slice.bins) {
    bin_z.push_back(bin.x);
    bin_r.push_back(bin.force_n);
  }
  const DisplayUnit z_unit = choose_display_unit("m", largest_abs({&samples.x, &bin_z}));
  const DisplayUnit r_unit = choose_display_unit("N", largest_abs({&samples.y, &bin_r}));
  const DisplayUnit band_unit = choose_display_unit("m/s", slice.velocity_band_m_s);
  const bool about_mean = review && review->campaign.z_about_mean;
  stiffness_plot_->xAxis->setLabel(
      (about_mean ? tr("z \u2212 z\u0304 [%1]") : tr("z [%1]")).arg(qtext(z_unit.symbol)));
  stiffness_plot_->yAxis->setLabel(tr("restoring force R [%1]").arg(force_unit(review, r_unit)));
  const auto to_display = [](const std::vector<double>& v, const DisplayUnit& unit) {
    QVector<double> out(qsizetype(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) out[qsizetype(i)] = unit.to_display(v[i]);
    return out;
  };
  QCPGraph* cloud = stiffness_plot_->addGraph();
  cloud->setName(tr("samples, |\u017c| < \u03b5_s = %1 %2 (%3)")
                     .arg(band_unit.to_display(slice.velocity_band_m_s), 0, 'g', 3)
                     .arg(qtext(band_unit.symbol))
                     .arg(samples.selected));
  cloud->setLineStyle(QCPGraph::lsNone);
  cloud->setScatterStyle(disc_markers(kSampleColour, 2));
  cloud->setData(to_display(samples.x, z_unit), to_display(samples.y, r_unit));
  QCPGraph* bins = stiffness_plot_->addGraph();
  bins->setName(tr("bin means (%1 bins)").arg(slice.bins.size()));
  bins->setLineStyle(QCPGraph::lsNone);
  bins->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, QColor(0, 60, 140), 5));
  bins->setData(to_display(bin_z, z_unit), to_display(bin_r, r_unit), true);
  QVector<double> fit_z, fit_r;
  for (int i = 0; i <= kCurvePoints; ++i) {
    const double z = slice.z_min_m + (slice.z_max_m - slice.z_min_m) * i / kCurvePoints;
    fit_z.push_back(z_unit.to_display(z));
    fit_r.push_back(r_unit.to_display(slice.fit.value(z)));
  }
  QCPGraph* fit = stiffness_plot_->addGraph();
  fit->setName(tr("fitted K(z), eq. (2)"));
  fit->setPen(QPen(kFitColour, 2.0));
  fit->setData(fit_z, fit_r, true);
  stiffness_plot_->rescaleAxes();
  const QCPRange r_range = stiffness_plot_->yAxis->range();
  fit_axis(stiffness_plot_->xAxis, stiffness_plot_->xAxis->range().lower,
           stiffness_plot_->xAxis->range().upper);
  // Room above the data for the legend (three entries).
  stiffness_plot_->yAxis->setRange(r_range.lower - kRangeMargin * r_range.size(),
                                   r_range.upper + 0.35 * r_range.size());
  stiffness_label_->setText(qtext(stiffness_fit_text(
      slice, analysis::mass_basis(review->campaign) == analysis::MassBasis::PerUnitMass)));
  stiffness_plot_->replot(QCustomPlot::rpQueuedReplot);

  // Damping slices: samples and bin means of each, by equilibrium.
  if (campaign->damping.empty()) {
    set_plot_hint(damping_plot_, tr("The fitted K(z) has no stable zero in the travelled range"));
    damping_plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  set_plot_hint(damping_plot_, {});
  std::vector<ScatterPoints> clouds = review->slice_points.damping;
  clouds.resize(campaign->damping.size());
  double v_max = 0.0, d_max = 0.0;
  for (const ScatterPoints& cloud : clouds) {
    v_max = std::max(v_max, largest_abs({&cloud.x}));
    d_max = std::max(d_max, largest_abs({&cloud.y}));
  }
  const DisplayUnit v_unit = choose_display_unit("m/s", v_max);
  const DisplayUnit d_unit = choose_display_unit("N", d_max);
  damping_plot_->xAxis->setLabel(tr("\u017c [%1]").arg(qtext(v_unit.symbol)));
  damping_plot_->yAxis->setLabel(tr("D = R \u2212 K(z) [%1]").arg(force_unit(review, d_unit)));
  for (std::size_t i = 0; i < campaign->damping.size(); ++i) {
    const analysis::DampingSlice& d = campaign->damping[i];
    const QColor colour = kSliceColour[d.z_center_m < 0.0 ? 0 : 1];
    const QString where = tr("z\u0304 = %1 %2")
                              .arg(z_unit.to_display(d.z_center_m), 0, 'f', 2)
                              .arg(qtext(z_unit.symbol));
    QCPGraph* points = damping_plot_->addGraph();
    points->setName(tr("%1: samples (%2)").arg(where).arg(clouds[i].selected));
    points->setLineStyle(QCPGraph::lsNone);
    points->setScatterStyle(disc_markers(colour.lighter(140), 2));
    points->setData(to_display(clouds[i].x, v_unit), to_display(clouds[i].y, d_unit));
    std::vector<double> bin_v, bin_d;
    for (const analysis::SliceBin& bin : d.bins) {
      bin_v.push_back(bin.x);
      bin_d.push_back(bin.force_n);
    }
    QCPGraph* means = damping_plot_->addGraph();
    means->setName(tr("%1: bin means").arg(where));
    means->setPen(QPen(colour.darker(130), 1.5));
    means->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, colour.darker(130), 5));
    means->setData(to_display(bin_v, v_unit), to_display(bin_d, d_unit), true);
  }
  damping_plot_->rescaleAxes();
  const QCPRange d_range = damping_plot_->yAxis->range();
  fit_axis(damping_plot_->xAxis, damping_plot_->xAxis->range().lower,
           damping_plot_->xAxis->range().upper);
  damping_plot_->yAxis->setRange(
      d_range.lower - kRangeMargin * d_range.size(),
      d_range.upper + 0.12 * double(2 * campaign->damping.size() + 1) * d_range.size());
  damping_plot_->replot(QCustomPlot::rpQueuedReplot);
}

}  // namespace oscilab::ui

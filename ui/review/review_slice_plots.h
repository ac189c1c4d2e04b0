#pragma once

#include <QCoreApplication>
#include <QString>

#include "ui/display_units.h"
#include "ui/review/review_model.h"

class QCustomPlot;
class QLabel;
class QWidget;

namespace oscilab::ui {

/// The review's restoring-force page: the stiffness slice (R at small |ż| with its bin means and
/// the fitted K(z) of eq. (2), Fig. 7b) beside the damping slices at the stable equilibria
/// (D = R − K(z) against ż, Fig. 7c), the fitted K(z) with standard errors below. Shows a
/// campaign analysis; computes nothing (the points come from review_model.h). UI thread only.
class ReviewSlicePlots {
  Q_DECLARE_TR_FUNCTIONS(ReviewSlicePlots)

 public:
  /// Makes the plots and their page (owned by whoever takes page()).
  ReviewSlicePlots();

  QWidget* page() const { return page_; }
  QCustomPlot* stiffness_plot() const { return stiffness_plot_; }
  QCustomPlot* damping_plot() const { return damping_plot_; }
  QLabel* stiffness_label() const { return stiffness_label_; }

  /// Draws the slices of `review` (null: none; `running` says it is being computed).
  void show(const ReviewAnalysis* review, bool running);

 private:
  /// A force unit of the slice plots, per unit mass when the campaign has no mass ("mN/kg").
  static QString force_unit(const ReviewAnalysis* review, const DisplayUnit& unit);

  QWidget* page_ = nullptr;
  QCustomPlot* stiffness_plot_ = nullptr;
  QCustomPlot* damping_plot_ = nullptr;
  QLabel* stiffness_label_ = nullptr;
};

}  // namespace oscilab::ui

#pragma once

#include <utility>
#include <vector>

#include <QDialog>
#include <QString>

#include "analysis/figures/figure.h"

class QCustomPlot;
class QTabWidget;

namespace oscilab::ui {

/// Figures (analysis/figures/figure.h) in a window, one tab each, drawn by render_figure at their
/// own height (a tall one scrolls). The figures come ready-made; the dialog draws them. Each plot
/// exports from its context menu (ui/plots/plot_context_menu.h). UI thread only.
class FigureDialog : public QDialog {
  Q_OBJECT

 public:
  explicit FigureDialog(QWidget* parent = nullptr);

  /// Replaces the tabs: one per (tab name, figure), in order.
  void set_figures(const std::vector<std::pair<QString, figures::Figure>>& tabs);
  QTabWidget* tabs() const { return tabs_; }
  /// The plot of tab `index`, or null.
  QCustomPlot* plot(int index) const;

 private:
  QTabWidget* tabs_ = nullptr;
  std::vector<QCustomPlot*> plots_;
};

}  // namespace oscilab::ui

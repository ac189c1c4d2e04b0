#include "ui/identification/figure_dialog.h"

#include <QDialogButtonBox>
#include <QPushButton>
#include <QScrollArea>
#include <QTabWidget>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/figures/figure_png.h"
#include "ui/identification/figure_renderer.h"
#include "ui/plots/plot_context_menu.h"

namespace oscilab::ui {

FigureDialog::FigureDialog(QWidget* parent) : QDialog(parent) {
  tabs_ = new QTabWidget;
  auto* buttons = new QDialogButtonBox;
  QPushButton* export_button =
      buttons->addButton(tr("Export figure\u2026"), QDialogButtonBox::ActionRole);
  buttons->addButton(QDialogButtonBox::Close);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::close);
  connect(export_button, &QPushButton::clicked, this, [this] {
    if (QCustomPlot* p = plot(tabs_->currentIndex())) export_plot_interactively(*p, this);
  });
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(tabs_, 1);
  layout->addWidget(buttons);
  resize(1080, 900);
}

void FigureDialog::set_figures(const std::vector<std::pair<QString, figures::Figure>>& tabs) {
  while (tabs_->count() > 0) {
    QWidget* page = tabs_->widget(0);
    tabs_->removeTab(0);
    delete page;
  }
  plots_.clear();
  for (const auto& [name, figure] : tabs) {
    auto* plot = new QCustomPlot;
    render_figure(*plot, figure);
    // The figure's own height (panels of 220 to 520 px), so that a tall one scrolls rather than
    // squeezes its panels; the width follows the window.
    plot->setMinimumSize(600, figures::figure_height_px(figure));
    auto* scroll = new QScrollArea;
    scroll->setWidgetResizable(true);
    scroll->setWidget(plot);
    tabs_->addTab(scroll, name);
    plots_.push_back(plot);
  }
}

QCustomPlot* FigureDialog::plot(int index) const {
  return index >= 0 && index < static_cast<int>(plots_.size()) ? plots_[index] : nullptr;
}

}  // namespace oscilab::ui

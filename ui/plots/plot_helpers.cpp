#include "ui/plots/plot_helpers.h"

#include <algorithm>
#include <cmath>

#include <QEvent>
#include <QFontMetrics>

namespace oscilab::ui {
namespace {

// Keeps a small plot readable as it is resized: its title elided to its width ("…", the full
// title on hover) instead of cut at both ends, fewer ticks on a narrow or short axis so that
// their labels never run into each other, and a legend inside the axes that would cover most of
// them left out of the picture (its entries on hover instead). One per plot, found by its name.
class PlotFitter : public QObject {
 public:
  explicit PlotFitter(QCustomPlot* plot) : QObject(plot), plot_(plot) {
    setObjectName("plot_fitter");
    plot->installEventFilter(this);
    connect(plot, &QCustomPlot::beforeReplot, this, &PlotFitter::fit_legend);
  }

  static PlotFitter* of(QCustomPlot* plot) {
    auto* fitter = plot->findChild<PlotFitter*>("plot_fitter", Qt::FindDirectChildrenOnly);
    return fitter ? fitter : new PlotFitter(plot);
  }

  void set_title(QCPTextElement* title, const QString& text) {
    title_ = title;
    title_text_ = text;
    fit();
  }

  bool eventFilter(QObject* watched, QEvent* event) override {
    if (watched == plot_ && event->type() == QEvent::Resize) fit();
    return false;
  }

 private:
  void fit() {
    // About 90 px per tick label across, 45 px up (QCPAxisTicker takes the count as a hint).
    constexpr int kTickWidthPx = 90;
    constexpr int kTickHeightPx = 45;
    plot_->xAxis->ticker()->setTickCount(std::clamp(plot_->width() / kTickWidthPx, 2, 5));
    plot_->yAxis->ticker()->setTickCount(std::clamp(plot_->height() / kTickHeightPx, 2, 5));
    if (title_) {
      const QString shown =
          QFontMetrics(title_->font()).elidedText(title_text_, Qt::ElideRight, plot_->width() - 8);
      title_->setText(shown);
      title_elided_ = shown != title_text_;
    }
    update_tooltip();
  }

  // The legend's own visibility stays the plot's to decide; this hides its layer only.
  void fit_legend() {
    QCPLegend* legend = plot_->legend;
    QCPLayer* layer = legend ? legend->layer() : nullptr;
    if (!layer || legend->layout() != plot_->axisRect()->insetLayout()) return;
    const QSize needed = legend->minimumOuterSizeHint();
    const QRect axes = plot_->axisRect()->rect();
    // Covering more than 70 % of the axes' width or height, it hides what it names.
    const bool fits =
        needed.width() <= 0.7 * axes.width() && needed.height() <= 0.7 * axes.height();
    legend_hidden_ = legend->visible() && legend->itemCount() > 0 && !fits;
    if (layer->visible() == !legend_hidden_) return;
    layer->setVisible(!legend_hidden_);
    update_tooltip();
  }

  void update_tooltip() {
    QStringList lines;
    if (title_elided_) lines << title_text_;
    if (legend_hidden_) {
      for (int i = 0; i < plot_->legend->itemCount(); ++i) {
        if (auto* item = qobject_cast<QCPPlottableLegendItem*>(plot_->legend->item(i))) {
          lines << QStringLiteral("\u2022 %1").arg(item->plottable()->name());
        }
      }
    }
    plot_->setToolTip(lines.join('\n'));
  }

  QCustomPlot* plot_;
  QCPTextElement* title_ = nullptr;
  QString title_text_;
  bool title_elided_ = false;
  bool legend_hidden_ = false;
};

}  // namespace

void set_plot_hint(QCustomPlot* plot, const QString& message) {
  QCPItemText* hint = nullptr;
  for (int i = 0; i < plot->itemCount(); ++i) {
    if (plot->item(i)->objectName() == "hint") hint = qobject_cast<QCPItemText*>(plot->item(i));
  }
  if (!hint) {
    hint = new QCPItemText(plot);
    hint->setObjectName("hint");
    hint->position->setType(QCPItemPosition::ptAxisRectRatio);
    hint->position->setCoords(0.5, 0.5);
    hint->setColor(Qt::gray);
    hint->setClipToAxisRect(false);
  }
  hint->setText(message);
  hint->setVisible(!message.isEmpty());
}

QCPScatterStyle disc_markers(const QColor& colour, double size) {
  return QCPScatterStyle(QCPScatterStyle::ssDisc, colour, colour, size);
}

QCPTextElement* add_plot_title(QCustomPlot* plot, const QString& title) {
  plot->plotLayout()->insertRow(0);
  QFont font = plot->font();
  font.setBold(true);
  auto* element = new QCPTextElement(plot, title, font);
  plot->plotLayout()->addElement(0, 0, element);
  PlotFitter::of(plot)->set_title(element, title);
  return element;
}

void frame_axes(QCustomPlot* plot, const QString& x_label, const QString& y_label) {
  plot->xAxis->setLabel(x_label);
  plot->yAxis->setLabel(y_label);
  plot->xAxis->setNumberFormat("gb");
  plot->yAxis->setNumberFormat("gb");
  PlotFitter::of(plot);
  for (QCPAxis* axis : {plot->xAxis2, plot->yAxis2}) {  // a frame: top and right as lines
    axis->setVisible(true);
    axis->setTicks(false);
    axis->setTickLabels(false);
  }
}

void fit_axis(QCPAxis* axis, double lo, double hi, WhenEmpty when_empty, double margin) {
  if (!(lo <= hi)) {
    if (when_empty == WhenEmpty::Unit) axis->setRange(-1.0, 1.0);
    return;
  }
  const double pad = hi > lo ? margin * (hi - lo) : (hi != 0.0 ? 0.1 * std::abs(hi) : 1.0);
  axis->setRange(lo - pad, hi + pad);
}

}  // namespace oscilab::ui

#include "ui/plot_theme.h"

#include <utility>

#include <QActionGroup>
#include <QApplication>
#include <QEvent>
#include <QMenu>
#include <QStyle>
#include <QStyleFactory>

#include <qcustomplot.h>

namespace oscilab::ui {
namespace {

// The colours a plot was last drawn in, kept on the plot.
constexpr const char* kBaseProperty = "oscilab_palette_base";
constexpr const char* kTextProperty = "oscilab_palette_text";
constexpr const char* kFollowsProperty = "oscilab_palette_follows";
// An item drawn in the palette's colours (draw_in_palette_colours).
constexpr const char* kPaletteItemProperty = "oscilab_palette_item";

// The grid: about a fifth of the way from the background to the text (light grey on white).
QColor grid_colour(const QColor& base, const QColor& text) {
  const auto mix = [](int b, int t) { return b + (t - b) * 22 / 100; };
  return QColor(mix(base.red(), text.red()), mix(base.green(), text.green()),
                mix(base.blue(), text.blue()));
}

// The colours to replace: the previous palette's and QCustomPlot's defaults (what a plot rebuilt
// since, a new axis rect or legend, starts with), and what replaces them.
struct Recolouring {
  QColor old_base, old_text, old_grid;
  QColor base, text, grid;
  QColor text_for(const QColor& c) const {
    return c == old_text || c == QColor(Qt::black) ? text : c;
  }
  QColor base_for(const QColor& c) const {
    return c == old_base || c == QColor(Qt::white) ? base : c;
  }
  QPen pen(QPen pen) const {
    pen.setColor(text_for(pen.color()));
    return pen;
  }
  QPen grid_pen(QPen pen) const {
    if (pen.color() == old_grid || pen.color() == QColor(200, 200, 200)) pen.setColor(grid);
    return pen;
  }
};

void recolour(QCPAxis& axis, const Recolouring& r) {
  axis.setBasePen(r.pen(axis.basePen()));
  axis.setTickPen(r.pen(axis.tickPen()));
  axis.setSubTickPen(r.pen(axis.subTickPen()));
  axis.setTickLabelColor(r.text_for(axis.tickLabelColor()));
  axis.setLabelColor(r.text_for(axis.labelColor()));
  axis.grid()->setPen(r.grid_pen(axis.grid()->pen()));
  axis.grid()->setSubGridPen(r.grid_pen(axis.grid()->subGridPen()));
  axis.grid()->setZeroLinePen(r.grid_pen(axis.grid()->zeroLinePen()));
}

void recolour(QCPLayoutElement& element, const Recolouring& r) {
  if (auto* legend = qobject_cast<QCPLegend*>(&element)) {
    legend->setBrush(QBrush(r.base_for(legend->brush().color())));
    legend->setBorderPen(r.pen(legend->borderPen()));
    legend->setTextColor(r.text_for(legend->textColor()));
    for (int j = 0; j < legend->itemCount(); ++j) {
      legend->item(j)->setTextColor(r.text_for(legend->item(j)->textColor()));
    }
  } else if (auto* title = qobject_cast<QCPTextElement*>(&element)) {
    title->setTextColor(r.text_for(title->textColor()));
  } else if (auto* rect = qobject_cast<QCPAxisRect*>(&element)) {
    for (QCPAxis* axis : rect->axes()) recolour(*axis, r);
  }
}

// A cursor item's pen in the text colour and its brush in the base colour, alphas kept.
void recolour(QCPAbstractItem& item, const Recolouring& r) {
  const auto with_alpha = [](QColor c, int alpha) {
    c.setAlpha(alpha);
    return c;
  };
  if (auto* line = qobject_cast<QCPItemStraightLine*>(&item)) {
    QPen pen = line->pen();
    pen.setColor(with_alpha(r.text, pen.color().alpha()));
    line->setPen(pen);
  } else if (auto* tracer = qobject_cast<QCPItemTracer*>(&item)) {
    QPen pen = tracer->pen();
    pen.setColor(with_alpha(r.text, pen.color().alpha()));
    tracer->setPen(pen);
    QBrush brush = tracer->brush();
    if (brush.style() != Qt::NoBrush) {
      brush.setColor(with_alpha(r.base, brush.color().alpha()));
      tracer->setBrush(brush);
    }
  }
}

// Draws `plot` in `palette`'s colours (no replot).
void recolour(QCustomPlot& plot, const QPalette& palette) {
  Recolouring r;
  r.base = palette.color(QPalette::Base);
  r.text = palette.color(QPalette::Text);
  r.grid = grid_colour(r.base, r.text);
  const QVariant old_base = plot.property(kBaseProperty);
  r.old_base = old_base.isValid() ? old_base.value<QColor>() : QColor(Qt::white);
  const QVariant old_text = plot.property(kTextProperty);
  r.old_text = old_text.isValid() ? old_text.value<QColor>() : QColor(Qt::black);
  r.old_grid = grid_colour(r.old_base, r.old_text);
  plot.setBackground(QBrush(r.base));
  for (QCPLayoutElement* element : plot.plotLayout()->elements(true)) {
    if (element) recolour(*element, r);
  }
  for (int i = 0; i < plot.itemCount(); ++i) {
    if (QCPAbstractItem* item = plot.item(i); item->property(kPaletteItemProperty).toBool()) {
      recolour(*item, r);
    }
  }
  plot.setProperty(kBaseProperty, r.base);
  plot.setProperty(kTextProperty, r.text);
}

}  // namespace

void apply_palette(QCustomPlot& plot, const QPalette& palette) {
  recolour(plot, palette);
  if (!plot.property(kFollowsProperty).toBool()) {
    // What the plot builds later (new axis rects, legends, titles) follows at each replot.
    plot.setProperty(kFollowsProperty, true);
    QObject::connect(&plot, &QCustomPlot::beforeReplot, &plot,
                     [p = &plot] { recolour(*p, p->palette()); });
  }
  plot.replot(QCustomPlot::rpQueuedReplot);
}

void draw_in_palette_colours(QCPAbstractItem& item) {
  item.setProperty(kPaletteItemProperty, true);
  if (QCustomPlot* plot = item.parentPlot()) {
    Recolouring r;
    r.base = plot->palette().color(QPalette::Base);
    r.text = plot->palette().color(QPalette::Text);
    recolour(item, r);
  }
}

PlotPalettes::PlotPalettes(QObject* parent) : QObject(parent) {
  if (QCoreApplication* app = QCoreApplication::instance()) app->installEventFilter(this);
}

PlotPalettes::~PlotPalettes() {
  if (QCoreApplication* app = QCoreApplication::instance()) app->removeEventFilter(this);
}

bool PlotPalettes::eventFilter(QObject* watched, QEvent* event) {
  // Only two event types matter; everything else passes untouched (this sees every event).
  const QEvent::Type type = event->type();
  if (type != QEvent::Show && type != QEvent::PaletteChange) return false;
  if (auto* plot = qobject_cast<QCustomPlot*>(watched)) apply_palette(*plot, plot->palette());
  return false;
}

// The palette the application had before the first theme was chosen.
const QPalette& system_palette() {
  static const QPalette system = QApplication::palette();
  return system;
}

void apply_theme(Theme theme) {
  QPalette palette = system_palette();
  if (theme == Theme::Light) {
    if (QStyle* fusion = QStyleFactory::create(QStringLiteral("Fusion"))) {
      palette = fusion->standardPalette();
      delete fusion;
    }
  } else if (theme == Theme::Dark) {
    const QColor window(53, 53, 53), base(35, 35, 35), text(230, 230, 230);
    palette = QPalette(text, window, window.lighter(130), window.darker(150), window.darker(120),
                       text, Qt::white, base, window);
    palette.setColor(QPalette::Highlight, QColor(42, 130, 218));
    palette.setColor(QPalette::HighlightedText, Qt::black);
    palette.setColor(QPalette::ToolTipBase, window);
    palette.setColor(QPalette::ToolTipText, text);
    palette.setColor(QPalette::Link, QColor(86, 156, 214));
    palette.setColor(QPalette::PlaceholderText, text.darker(160));
    palette.setColor(QPalette::Disabled, QPalette::Text, text.darker(170));
    palette.setColor(QPalette::Disabled, QPalette::ButtonText, text.darker(170));
    palette.setColor(QPalette::Disabled, QPalette::WindowText, text.darker(170));
  }
  QApplication::setPalette(palette);
}

QMenu* add_theme_menu(QMenu& menu) {
  system_palette();
  QMenu* themes = menu.addMenu(QObject::tr("&Theme"));
  themes->setObjectName("theme_menu");
  auto* group = new QActionGroup(themes);
  for (const auto& [name, theme] : {std::pair{QObject::tr("&System"), Theme::System},
                                    std::pair{QObject::tr("&Light"), Theme::Light},
                                    std::pair{QObject::tr("&Dark"), Theme::Dark}}) {
    QAction* action = themes->addAction(name, [theme] { apply_theme(theme); });
    action->setCheckable(true);
    action->setChecked(theme == Theme::System);
    group->addAction(action);
  }
  return themes;
}

}  // namespace oscilab::ui

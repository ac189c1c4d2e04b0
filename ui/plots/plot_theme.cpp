#include "ui/plots/plot_theme.h"

#include <algorithm>
#include <cmath>
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
constexpr const char* kLegibleTextProperty = "oscilab_legible_text";

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

// WCAG 2.x relative luminance of an sRGB colour and the contrast ratio of two colours (1 to 21).
double relative_luminance(const QColor& c) {
  const auto linear = [](double v) {
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * linear(c.redF()) + 0.7152 * linear(c.greenF()) + 0.0722 * linear(c.blueF());
}
double contrast_ratio(const QColor& a, const QColor& b) {
  const double la = relative_luminance(a), lb = relative_luminance(b);
  return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

// WCAG's least contrast for graphics (1.4.11): what a data line needs against its background;
// and for text (1.4.3), what a label in a data colour needs.
constexpr double kLeastDataContrast = 3.0;
constexpr double kLeastTextContrast = 4.5;

// A data colour that shows on `base`: as it is when its contrast with the base is at least 3:1;
// otherwise its HSL lightness mirrored (a dark blue on a dark background becomes a light blue of
// the same hue, and darker shades of one colour become lighter ones, still apart), then moved
// further from the base until it reaches 3:1. Alpha is kept.
QColor legible_on(const QColor& colour, const QColor& base, double least = kLeastDataContrast) {
  if (contrast_ratio(colour, base) >= least) return colour;
  const QColor hsl = colour.toHsl();
  const bool dark_base = relative_luminance(base) < 0.18;
  double lightness = 1.0 - hsl.lightnessF();
  QColor out = QColor::fromHslF(hsl.hslHueF(), hsl.hslSaturationF(), lightness, hsl.alphaF());
  for (int i = 0; i < 20 && contrast_ratio(out, base) < least; ++i) {
    lightness = std::clamp(lightness + (dark_base ? 0.05 : -0.05), 0.0, 1.0);
    out = QColor::fromHslF(hsl.hslHueF(), hsl.hslSaturationF(), lightness, hsl.alphaF());
  }
  return out.toRgb();
}

// The colour a plottable shows in its colour `slot` on `base`: its own colour (what the plot
// set, remembered on the plottable so that a theme switched back restores it) made legible.
QColor shown_colour(QObject& owner, const char* slot, const QColor& current, const QColor& base,
                    double least = kLeastDataContrast) {
  const QByteArray own_key = QByteArray("oscilab_own_") + slot;
  const QByteArray shown_key = QByteArray("oscilab_shown_") + slot;
  const QVariant shown = owner.property(shown_key.constData());
  // A colour the plot set since (not the one shown last) is its own new colour.
  const QColor own = shown.isValid() && shown.value<QColor>() == current
                         ? owner.property(own_key.constData()).value<QColor>()
                         : current;
  const QColor out = legible_on(own, base, least);
  owner.setProperty(own_key.constData(), own);
  owner.setProperty(shown_key.constData(), out);
  return out;
}

// A pen, and a solid brush of at least 50 % alpha, legible on `base` (a fainter fill is a
// background of its own and stays), their own colours kept under `slot` on `owner`.
QPen legible_pen(QObject& owner, const char* slot, QPen pen, const QColor& base) {
  if (pen.style() != Qt::NoPen) pen.setColor(shown_colour(owner, slot, pen.color(), base));
  return pen;
}
QBrush legible_brush(QObject& owner, const char* slot, QBrush brush, const QColor& base) {
  if (brush.style() == Qt::SolidPattern && brush.color().alpha() >= 128) {
    brush.setColor(shown_colour(owner, slot, brush.color(), base));
  }
  return brush;
}

// A plottable's lines, fills and markers legible on `base`.
void recolour(QCPAbstractPlottable& plottable, const QColor& base) {
  plottable.setPen(legible_pen(plottable, "pen", plottable.pen(), base));
  plottable.setBrush(legible_brush(plottable, "brush", plottable.brush(), base));
  const auto markers = [&](QCPScatterStyle style) {
    if (style.isNone()) return style;
    // A marker without a pen of its own draws with the plottable's (made legible above);
    // setting one would replace it.
    if (style.isPenDefined()) {
      style.setPen(legible_pen(plottable, "marker_pen", style.pen(), base));
    }
    style.setBrush(legible_brush(plottable, "marker_brush", style.brush(), base));
    return style;
  };
  if (auto* graph = qobject_cast<QCPGraph*>(&plottable)) {
    graph->setScatterStyle(markers(graph->scatterStyle()));
  } else if (auto* curve = qobject_cast<QCPCurve*>(&plottable)) {
    curve->setScatterStyle(markers(curve->scatterStyle()));
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
    QCPAbstractItem* item = plot.item(i);
    if (item->property(kPaletteItemProperty).toBool()) recolour(*item, r);
    if (item->property(kLegibleTextProperty).toBool()) {
      if (auto* text = qobject_cast<QCPItemText*>(item)) {
        text->setColor(shown_colour(*text, "color", text->color(), r.base, kLeastTextContrast));
      }
    }
  }
  for (int i = 0; i < plot.plottableCount(); ++i) recolour(*plot.plottable(i), r.base);
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

void draw_legibly(QCPItemText& text) {
  text.setProperty(kLegibleTextProperty, true);
  if (QCustomPlot* plot = text.parentPlot()) {
    text.setColor(shown_colour(text, "color", text.color(), plot->palette().color(QPalette::Base),
                               kLeastTextContrast));
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

#pragma once

#include <QObject>
#include <QPalette>

class QCPAbstractItem;
class QCPItemText;
class QCustomPlot;
class QMenu;

namespace oscilab::ui {

/// Draws `plot` in the colours of `palette`: its background and legends in the base colour, its
/// axes, ticks, labels, titles and legend text in the text colour, the grid between the two. A
/// colour the plot chose itself (a channel's title in its curve's colour) stays: only what is in
/// the previous palette's colours or QCustomPlot's defaults (black, white, the grid's grey) is
/// replaced, again before each replot (so that axes and legends the plot builds later follow
/// too; a plot that draws something in black on purpose gets it in the text colour). Data lines,
/// solid fills and markers with less than WCAG's 3:1 contrast against the background (a dark
/// blue loop on a dark theme) are drawn in their colour's mirrored lightness instead, and get
/// their own colour back on a background they show on. Replots.
void apply_palette(QCustomPlot& plot, const QPalette& palette);

/// Draws `item` (a cursor line, a tracer) in the palette's colours from now on: its pen in the
/// text colour, its brush (if any) in the base colour, each with the alpha it had; apply_palette
/// keeps it so through theme changes. Without it a cursor drawn dark grey vanishes on a dark
/// theme.
void draw_in_palette_colours(QCPAbstractItem& item);

/// Draws `text` (a label in a data colour: a well's name in the well's colour) in that colour
/// made legible on the plot's background from now on: as it is where it has WCAG's 4.5:1 for
/// text, otherwise its mirrored lightness moved until it has; apply_palette keeps it so, and a
/// background it shows on gets its own colour back.
void draw_legibly(QCPItemText& text);

/// Every QCustomPlot of the application follows its palette: an event filter on the application
/// object applies it when a plot is first shown and whenever its palette changes (the system's
/// dark or light scheme, View ▸ Theme). One per application; the filter goes with the object.
/// UI thread only.
class PlotPalettes : public QObject {
  Q_OBJECT

 public:
  explicit PlotPalettes(QObject* parent = nullptr);
  ~PlotPalettes() override;

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
};

/// The application's colour scheme: the system's (the palette the application started with), or
/// Fusion's light or a dark one. Sets the application palette; every widget and, through
/// PlotPalettes, every plot follows it.
enum class Theme { System, Light, Dark };
void apply_theme(Theme theme);

/// A "Theme" submenu of `menu` with System (checked), Light and Dark, one checked at a time;
/// returns it. Keeps the system's palette first (call it before the palette changes).
QMenu* add_theme_menu(QMenu& menu);

}  // namespace oscilab::ui

// The PNG figure writer's drawing with cairo (figure_cairo.h), compiled into oscilab_png_module.
#include "analysis/figures/figure_cairo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include <cairo.h>

namespace oscilab::figures {
namespace {

// Layout in pixels (the app's interactive figures use the same proportions).
constexpr double kTitleRowPx = kFigureTitleRowPx;
constexpr double kPanelTitleRowPx = 22.0;  // a panel's title, inside its panel_height_px
constexpr double kMarginLeftPx = 82.0;     // y tick labels and the rotated y label
constexpr double kMarginRightPx = 18.0;
constexpr double kMarginTopPx = 8.0;
constexpr double kMarginBottomPx = 50.0;  // x tick labels and the x label
constexpr double kFontPx = 13.0;          // 10 pt at 96 dpi
constexpr double kTitleFontPx = 15.0;
constexpr double kLegendRowPx = 18.0;
constexpr double kLegendSamplePx = 26.0;

struct Range {
  double lower = std::numeric_limits<double>::infinity();
  double upper = -std::numeric_limits<double>::infinity();
  bool empty() const { return !(lower <= upper); }
  void expand(double v) {
    lower = std::min(lower, v);
    upper = std::max(upper, v);
  }
  // A margin of `fraction` of the span on each side; a single value gets ±10 % of itself (or ±1).
  void pad(double fraction) {
    const double span = upper - lower;
    if (span > 0.0) {
      lower -= fraction * span;
      upper += fraction * span;
      return;
    }
    const double half = lower != 0.0 ? 0.1 * std::abs(lower) : 1.0;
    lower -= half;
    upper += half;
  }
};

struct Box {
  double left, top, width, height;
  double right() const { return left + width; }
  double bottom() const { return top + height; }
};

void set_color(cairo_t* cr, const Rgb& c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c.red / 255.0, c.green / 255.0, c.blue / 255.0, alpha);
}

void set_font(cairo_t* cr, double size_px, bool bold) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size_px);
}

double text_width(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  return e.x_advance;
}

// Draws `text` with its anchor at (x, y): h_align 0 left, 0.5 centre, 1 right; y is the middle
// of a line of the current font.
void draw_text(cairo_t* cr, const std::string& text, double x, double y, double h_align) {
  if (text.empty()) return;
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  cairo_move_to(cr, x - h_align * text_width(cr, text), y + 0.5 * (fe.ascent - fe.descent));
  cairo_show_text(cr, text.c_str());
}

// A tick step of 1, 2 or 5 × 10^k giving about `target` intervals over `span`.
double tick_step(double span, int target) {
  const double raw = span / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / magnitude;
  return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * magnitude;
}

std::vector<double> ticks(const Range& r, int target) {
  const double step = tick_step(r.upper - r.lower, target);
  std::vector<double> out;
  if (!(step > 0.0) || !std::isfinite(step)) return out;
  for (double k = std::ceil(r.lower / step); k * step <= r.upper + 1e-9 * step; k += 1.0) {
    const double v = k * step;
    out.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);  // no "-0"
    if (out.size() > 50) break;
  }
  return out;
}

// Tick labels with as many decimals as the step needs; scientific for very large or small.
std::string tick_label(double v, double step, double largest) {
  char buffer[48];
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  if (largest >= 1e6 || decimals > 5) {
    std::snprintf(buffer, sizeof buffer, "%.3g", v);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  }
  return buffer;
}

struct Mapping {
  Box box;
  Range x, y;
  double px(double v) const { return box.left + (v - x.lower) / (x.upper - x.lower) * box.width; }
  double py(double v) const {
    return box.bottom() - (v - y.lower) / (y.upper - y.lower) * box.height;
  }
};

bool finite_point(const FigureSeries& s, std::size_t i) {
  return std::isfinite(s.x[i]) && std::isfinite(s.y[i]);
}

void draw_marker(cairo_t* cr, const FigureSeries& s, double x, double y) {
  const Rgb c = palette_color(s.color);
  const double radius = 0.5 * s.width_px;
  cairo_new_sub_path(cr);
  cairo_arc(cr, x, y, radius, 0.0, 2.0 * M_PI);
  if (s.style == FigureSeries::Style::Dots) {
    set_color(cr, c);
    cairo_fill(cr);
  } else {  // Markers: open circles, white inside
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_fill_preserve(cr);
    set_color(cr, c);
    cairo_set_line_width(cr, 1.5);
    cairo_stroke(cr);
  }
}

void set_line_style(cairo_t* cr, const FigureSeries& s) {
  set_color(cr, palette_color(s.color));
  cairo_set_line_width(cr, s.width_px);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  if (s.style == FigureSeries::Style::DashedLine) {
    const double dash[] = {4.0 * s.width_px, 2.0 * s.width_px};
    cairo_set_dash(cr, dash, 2, 0.0);
  } else {
    cairo_set_dash(cr, nullptr, 0, 0.0);
  }
}

void draw_series(cairo_t* cr, const Mapping& m, const FigureSeries& s) {
  const std::size_t n = std::min(s.x.size(), s.y.size());
  if (s.style == FigureSeries::Style::Dots || s.style == FigureSeries::Style::Markers) {
    for (std::size_t i = 0; i < n; ++i) {
      if (finite_point(s, i)) draw_marker(cr, s, m.px(s.x[i]), m.py(s.y[i]));
    }
    return;
  }
  set_line_style(cr, s);
  bool pen_down = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!finite_point(s, i)) {  // a gap
      pen_down = false;
      continue;
    }
    if (pen_down) {
      cairo_line_to(cr, m.px(s.x[i]), m.py(s.y[i]));
    } else {
      cairo_move_to(cr, m.px(s.x[i]), m.py(s.y[i]));
      pen_down = true;
    }
  }
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0.0);
}

void draw_legend(cairo_t* cr, const Box& axes, const FigurePanel& panel) {
  std::vector<const FigureSeries*> entries;
  for (const FigureSeries& s : panel.series) {
    if (!s.name.empty()) entries.push_back(&s);
  }
  if (!panel.legend || entries.empty()) return;
  set_font(cr, kFontPx, false);
  double text = 0.0;
  for (const FigureSeries* s : entries) text = std::max(text, text_width(cr, s->name));
  const double width = text + kLegendSamplePx + 18.0;
  const double height = kLegendRowPx * static_cast<double>(entries.size()) + 8.0;
  using Corner = FigurePanel::Corner;
  const Corner c = panel.legend_corner;
  const bool left = c == Corner::TopLeft || c == Corner::BottomLeft;
  const bool top = c == Corner::TopLeft || c == Corner::TopRight;
  const double x0 = left ? axes.left + 8.0 : axes.right() - 8.0 - width;
  const double y0 = top ? axes.top + 8.0 : axes.bottom() - 8.0 - height;
  cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, width, height);
  cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 220.0 / 255.0);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 1.0);
  cairo_stroke(cr);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const FigureSeries& s = *entries[i];
    const double y = y0 + 4.0 + (static_cast<double>(i) + 0.5) * kLegendRowPx;
    const double sample_left = x0 + 6.0;
    if (s.style == FigureSeries::Style::Line || s.style == FigureSeries::Style::DashedLine) {
      set_line_style(cr, s);
      cairo_move_to(cr, sample_left, y);
      cairo_line_to(cr, sample_left + kLegendSamplePx - 4.0, y);
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0.0);
    } else {
      draw_marker(cr, s, sample_left + 0.5 * (kLegendSamplePx - 4.0), y);
    }
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    draw_text(cr, s.name, sample_left + kLegendSamplePx + 2.0, y, 0.0);
  }
}

void draw_axes(cairo_t* cr, const Mapping& m, const FigurePanel& panel) {
  const std::vector<double> x_ticks = ticks(m.x, 6);
  const std::vector<double> y_ticks = ticks(m.y, 5);
  // Grid: light grey dotted lines at the ticks.
  const double dots[] = {1.0, 3.0};
  cairo_set_dash(cr, dots, 2, 0.0);
  cairo_set_line_width(cr, 1.0);
  cairo_set_source_rgb(cr, 0.78, 0.78, 0.78);
  for (double v : x_ticks) {
    const double x = std::round(m.px(v)) + 0.5;
    cairo_move_to(cr, x, m.box.top);
    cairo_line_to(cr, x, m.box.bottom());
  }
  for (double v : y_ticks) {
    const double y = std::round(m.py(v)) + 0.5;
    cairo_move_to(cr, m.box.left, y);
    cairo_line_to(cr, m.box.right(), y);
  }
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0.0);
  // Frame and ticks.
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_rectangle(cr, std::round(m.box.left) + 0.5, std::round(m.box.top) + 0.5,
                  std::round(m.box.width), std::round(m.box.height));
  for (double v : x_ticks) {
    const double x = std::round(m.px(v)) + 0.5;
    cairo_move_to(cr, x, m.box.bottom());
    cairo_line_to(cr, x, m.box.bottom() - 5.0);
  }
  for (double v : y_ticks) {
    const double y = std::round(m.py(v)) + 0.5;
    cairo_move_to(cr, m.box.left, y);
    cairo_line_to(cr, m.box.left + 5.0, y);
  }
  cairo_stroke(cr);
  // Tick labels and axis labels.
  set_font(cr, kFontPx, false);
  const double x_largest = std::max(std::abs(m.x.lower), std::abs(m.x.upper));
  const double y_largest = std::max(std::abs(m.y.lower), std::abs(m.y.upper));
  for (double v : x_ticks) {
    const double step = tick_step(m.x.upper - m.x.lower, 6);
    draw_text(cr, tick_label(v, step, x_largest), m.px(v), m.box.bottom() + 13.0, 0.5);
  }
  for (double v : y_ticks) {
    const double step = tick_step(m.y.upper - m.y.lower, 5);
    draw_text(cr, tick_label(v, step, y_largest), m.box.left - 6.0, m.py(v), 1.0);
  }
  draw_text(cr, panel.x_label, m.box.left + 0.5 * m.box.width, m.box.bottom() + 36.0, 0.5);
  cairo_save(cr);
  cairo_translate(cr, 14.0, m.box.top + 0.5 * m.box.height);
  cairo_rotate(cr, -0.5 * M_PI);
  draw_text(cr, panel.y_label, 0.0, 0.0, 0.5);
  cairo_restore(cr);
}

void draw_panel(cairo_t* cr, const FigurePanel& panel, double top, double width, double height) {
  if (!panel.title.empty()) {
    set_font(cr, kFontPx, false);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    draw_text(cr, panel.title, 0.5 * width, top + 0.5 * kPanelTitleRowPx + 2.0, 0.5);
    top += kPanelTitleRowPx;
    height -= kPanelTitleRowPx;
  }
  Mapping m;
  m.box = {kMarginLeftPx, top + kMarginTopPx, std::max(1.0, width - kMarginLeftPx - kMarginRightPx),
           std::max(1.0, height - kMarginTopPx - kMarginBottomPx)};
  for (const FigureSeries& s : panel.series) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (!finite_point(s, i)) continue;
      m.x.expand(s.x[i]);
      m.y.expand(s.y[i]);
    }
  }
  if (m.x.empty()) m.x = {0.0, 1.0};  // an empty panel still shows its axes
  if (m.y.empty()) m.y = {0.0, 1.0};
  m.x.pad(0.04);
  m.y.pad(0.06);
  draw_axes(cr, m, panel);
  cairo_save(cr);
  cairo_rectangle(cr, m.box.left, m.box.top, m.box.width, m.box.height);
  cairo_clip(cr);
  for (const FigureSeries& s : panel.series) draw_series(cr, m, s);
  cairo_restore(cr);
  draw_legend(cr, m.box, panel);
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

}  // namespace

std::string draw_figure_png(const Figure& figure, int height_px, const std::string& path) {
  const int width = figure.width_px;
  const std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height_px));
  const std::unique_ptr<cairo_t, ContextDeleter> context(cairo_create(surface.get()));
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);
  double top = 0.0;
  if (!figure.title.empty()) {
    set_font(cr, kTitleFontPx, true);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    draw_text(cr, figure.title, 0.5 * width, 0.5 * kTitleRowPx, 0.5);
    top = kTitleRowPx;
  }
  for (const FigurePanel& panel : figure.panels) {
    draw_panel(cr, panel, top, width, figure.panel_height_px);
    top += figure.panel_height_px;
  }
  cairo_surface_flush(surface.get());
  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS) {
    return std::string("cannot draw the figure (") + cairo_status_to_string(cairo_status(cr)) + ")";
  }
  const cairo_status_t written = cairo_surface_write_to_png(surface.get(), path.c_str());
  if (written != CAIRO_STATUS_SUCCESS) {
    return std::string("cannot write PNG (") + cairo_status_to_string(written) + ")";
  }
  return "";
}

}  // namespace oscilab::figures

// A Figure drawn into a QCustomPlot (ui/identification/figure_renderer), as the figures dialog
// shows it. Run under QT_QPA_PLATFORM=offscreen (set by ctest).
#include <cmath>
#include <limits>

#include <QApplication>
#include <QColor>
#include <QImage>
#include <QTest>

#include "analysis/figures/figure.h"
#include "analysis/figures/figure_png.h"
#include "ui/identification/figure_renderer.h"

#include <qcustomplot.h>

using oscilab::figures::Figure;
using oscilab::figures::FigurePanel;
using oscilab::figures::FigureSeries;

namespace {

// Pixels close to `color` (each channel within 40 of 255: antialiasing blends line edges).
int count_pixels(const QImage& image, const QColor& color) {
  int n = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      if (std::abs(c.red() - color.red()) < 40 && std::abs(c.green() - color.green()) < 40 &&
          std::abs(c.blue() - color.blue()) < 40) {
        ++n;
      }
    }
  }
  return n;
}

}  // namespace

class FigureRendererTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void drawsEachPanelsSeriesInItsOwnAxes() {
    Figure figure;
    figure.title = "test";
    figure.width_px = 600;
    figure.panel_height_px = 300;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // A curve that turns back in x (a fold) with a NaN gap, drawn in palette colour 1 (blue).
    FigurePanel a{"", "f0 [N]", "amplitude [mm]", {}, true};
    a.series.push_back(
        {"HBM", FigureSeries::Style::Line, 1, {0, 1, 2, 1.5, nan, 3}, {0, 1, 2, 3, nan, 4}, 3.0});
    // Dots in palette colour 2 (vermillion) in a second panel.
    FigurePanel b{"", "f0 [N]", "z [mm]", {}, true};
    b.series.push_back({"map", FigureSeries::Style::Dots, 2, {0, 1, 2, 3}, {1, 2, 1, 2}, 6.0});
    figure.panels = {a, b};
    QCustomPlot plot;
    oscilab::ui::render_figure(plot, figure);
    QCOMPARE(plot.axisRectCount(), 2);
    QCOMPARE(plot.plottableCount(), 3);  // the line breaks at NaN into two curves, and the dots
    const int height = oscilab::figures::figure_height_px(figure);
    QCOMPARE(height, 2 * 300 + 30);  // panels plus the title row
    const QImage image = plot.toPixmap(600, height).toImage();
    const int blue_top = count_pixels(image.copy(0, 0, 600, 330), QColor(0, 114, 178));
    const int red_bottom = count_pixels(image.copy(0, 330, 600, 300), QColor(213, 94, 0));
    QVERIFY2(blue_top > 100, qPrintable(QString::number(blue_top)));
    QVERIFY2(red_bottom > 20, qPrintable(QString::number(red_bottom)));
    QCOMPARE(count_pixels(image.copy(0, 330, 600, 300), QColor(0, 114, 178)), 0);
  }
};

QTEST_MAIN(FigureRendererTest)
#include "figure_renderer_test.moc"

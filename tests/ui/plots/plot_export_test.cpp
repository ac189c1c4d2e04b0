// Plot and table export (ui/plots/plot_export): a small QCustomPlot saved as PNG, PDF and SVG, each
// file checked by an independent reader (QImage, the PDF header, QXmlStreamReader), and a table
// as CSV. Run under QT_QPA_PLATFORM=offscreen (set by ctest).
#include <cmath>
#include <numbers>
#include <string>

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QImage>
#include <QPainter>
#include <QStandardItemModel>
#include <QSvgRenderer>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QXmlStreamReader>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "ui/plots/plot_export.h"

namespace {

const QColor kLineColor(0, 114, 178);  // Okabe & Ito blue, unlike anything else on the plot

// A sine on one graph, drawn 3 px wide in kLineColor.
void fill_plot(QCustomPlot& plot) {
  QVector<double> x, y;
  for (int i = 0; i <= 200; ++i) {
    x << i * 0.01;
    y << std::sin(2.0 * std::numbers::pi * i * 0.01);
  }
  QCPGraph* graph = plot.addGraph();
  graph->setData(x, y);
  graph->setPen(QPen(kLineColor, 3.0));
  plot.xAxis->setLabel(QStringLiteral("t [s]"));
  plot.yAxis->setLabel(QStringLiteral("z [mm]"));
  plot.rescaleAxes();
}

QByteArray read_all(const QString& path) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly)) return {};
  return file.readAll();
}

// The InputError message `action` throws, or "" when it throws none.
template <typename Action>
QString input_error_of(Action action) {
  try {
    action();
  } catch (const oscilab::InputError& error) {
    return QString::fromStdString(error.what());
  }
  return {};
}

// Pixels of `image` near kLineColor (antialiasing blends edges: within 40 per channel) outside
// `inside`, the axis rect grown by the pen's half width.
int line_pixels_outside(const QImage& image, const QRect& inside) {
  int count = 0;
  for (int yy = 0; yy < image.height(); ++yy) {
    for (int xx = 0; xx < image.width(); ++xx) {
      const QColor c = image.pixelColor(xx, yy);
      if (!inside.contains(xx, yy) && std::abs(c.red() - kLineColor.red()) < 40 &&
          std::abs(c.green() - kLineColor.green()) < 40 &&
          std::abs(c.blue() - kLineColor.blue()) < 40) {
        ++count;
      }
    }
  }
  return count;
}

}  // namespace

class PlotExportTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void writesPngOfTheRequestedSizeWithTheCurve() {
    QTemporaryDir dir;
    QCustomPlot plot;
    fill_plot(plot);
    const QString path = dir.filePath(QStringLiteral("plot.PNG"));  // extension case ignored
    oscilab::ui::export_plot(plot, path, 400, 250);
    const QImage image(path);
    QVERIFY(!image.isNull());
    QCOMPARE(image.size(), QSize(400, 250));
    int line_pixels = 0;  // antialiasing blends the edges: count pixels within 40 per channel
    for (int yy = 0; yy < image.height(); ++yy) {
      for (int xx = 0; xx < image.width(); ++xx) {
        const QColor c = image.pixelColor(xx, yy);
        if (std::abs(c.red() - kLineColor.red()) < 40 &&
            std::abs(c.green() - kLineColor.green()) < 40 &&
            std::abs(c.blue() - kLineColor.blue()) < 40) {
          ++line_pixels;
        }
      }
    }
    // A 3 px line across most of a 400 px wide axis rect covers well over 300 pixels.
    QVERIFY2(line_pixels > 300, qPrintable(QString::number(line_pixels)));
    QCOMPARE(QDir(dir.path()).entryList(QDir::Files).size(), 1);  // no temporary left
  }

  void writesPdf() {
    QTemporaryDir dir;
    QCustomPlot plot;
    fill_plot(plot);
    const QString path = dir.filePath(QStringLiteral("plot.pdf"));
    oscilab::ui::export_plot(plot, path, 400, 250);
    const QByteArray pdf = read_all(path);
    QVERIFY(pdf.startsWith("%PDF-"));
    QVERIFY(pdf.trimmed().endsWith("%%EOF"));
    QVERIFY(pdf.contains("/Type /Page") || pdf.contains("/Type/Page"));
  }

  void writesSvgWithTheCurveAsVectorPaths() {
    QTemporaryDir dir;
    QCustomPlot plot;
    fill_plot(plot);
    const QString path = dir.filePath(QStringLiteral("plot.svg"));
    oscilab::ui::export_plot(plot, path, 400, 250);
    QXmlStreamReader xml(read_all(path));
    QString root;
    int paths = 0;
    bool curve_colour = false;
    while (!xml.atEnd()) {
      if (xml.readNext() != QXmlStreamReader::StartElement) continue;
      if (root.isEmpty()) {
        root = xml.name().toString();
        QCOMPARE(xml.attributes().value(QStringLiteral("viewBox")).toString(),
                 QStringLiteral("0 0 400 250"));
      }
      if (xml.name() == QLatin1String("path") || xml.name() == QLatin1String("polyline")) {
        ++paths;
      }
      if (xml.attributes().value(QStringLiteral("stroke")) == QLatin1String("#0072b2")) {
        curve_colour = true;
      }
    }
    QVERIFY2(!xml.hasError(), qPrintable(xml.errorString()));
    QCOMPARE(root, QStringLiteral("svg"));
    QVERIFY2(paths > 0, "no path or polyline element");
    QVERIFY2(curve_colour, "the curve's stroke colour is missing: not drawn as a vector");
  }

  // A curve that runs past the axes (here: zoomed into the middle of a sine) is cut at the frame
  // in the SVG as on screen: the SVG, drawn by Qt's own renderer, has no curve pixel outside the
  // axis rect.
  void svgIsClippedToTheAxisRectLikeTheScreen() {
    QTemporaryDir dir;
    QCustomPlot plot;
    fill_plot(plot);
    plot.xAxis->setRange(0.4, 0.6);
    plot.yAxis->setRange(-0.3, 0.3);
    plot.resize(400, 250);
    plot.replot();  // lays out the axis rect
    const QRect rect = plot.axisRect()->rect().adjusted(-2, -2, 2, 2);
    QImage screen(400, 250, QImage::Format_ARGB32);
    screen.fill(Qt::white);
    {
      QCPPainter painter(&screen);
      plot.toPainter(&painter, 400, 250);
    }
    QCOMPARE(line_pixels_outside(screen, rect), 0);  // the screen's drawing clips
    const QString path = dir.filePath(QStringLiteral("zoomed.svg"));
    oscilab::ui::export_plot(plot, path, 400, 250);
    QSvgRenderer renderer(path);
    QVERIFY(renderer.isValid());
    QImage drawn(400, 250, QImage::Format_ARGB32);
    drawn.fill(Qt::white);
    {
      QPainter painter(&drawn);
      renderer.render(&painter);
    }
    QCOMPARE(line_pixels_outside(drawn, rect), 0);
  }

  // The export dialog proposes a file named after the plot: its object name, else its title,
  // else the tab it sits in, else its axes.
  void proposesAFileNameAfterThePlot() {
    using oscilab::ui::plot_file_name;
    QCustomPlot named;
    named.setObjectName(QStringLiteral("edc_positive_plot"));
    QCOMPARE(plot_file_name(named), QStringLiteral("edc-positive"));
    QCustomPlot titled;
    titled.plotLayout()->insertRow(0);
    titled.plotLayout()->addElement(
        0, 0, new QCPTextElement(&titled, QStringLiteral("Energy dissipated per cycle (Fig. 10)")));
    QCOMPARE(plot_file_name(titled), QStringLiteral("energy-dissipated-per-cycle-fig-10"));
    QTabWidget tabs;
    auto* in_tab = new QCustomPlot;
    tabs.addTab(in_tab, QStringLiteral("Cost slices (Fig. 13)"));
    QCOMPARE(plot_file_name(*in_tab), QStringLiteral("cost-slices-fig-13"));
    QCustomPlot axes;
    fill_plot(axes);
    QCOMPARE(plot_file_name(axes), QStringLiteral("z-mm-vs-t-s"));
    QCOMPARE(plot_file_name(QCustomPlot()), QStringLiteral("plot"));
  }

  void takesThePlotsOwnSizeWhenGivenNone() {
    QTemporaryDir dir;
    QCustomPlot plot;
    fill_plot(plot);
    plot.resize(321, 123);
    const QString path = dir.filePath(QStringLiteral("own.png"));
    oscilab::ui::export_plot(plot, path);
    QCOMPARE(QImage(path).size(), QSize(321, 123));
  }

  void throwsInputErrorOnAnUnknownExtensionOrAFailedWrite() {
    QTemporaryDir dir;
    QCustomPlot plot;
    fill_plot(plot);
    const QString gif = dir.filePath(QStringLiteral("plot.gif"));
    const QString message = input_error_of([&] { oscilab::ui::export_plot(plot, gif, 100, 100); });
    QVERIFY2(message.startsWith(gif + QStringLiteral(": unknown image format \"gif\"")),
             qPrintable(message));
    const QString none = dir.filePath(QStringLiteral("plot"));
    QVERIFY(input_error_of([&] {
              oscilab::ui::export_plot(plot, none, 100, 100);
            }).contains(QStringLiteral("unknown image format")));
    for (const char* name : {"no/dir/plot.png", "no/dir/plot.pdf", "no/dir/plot.svg"}) {
      const QString path = dir.filePath(QString::fromLatin1(name));
      const QString error = input_error_of([&] { oscilab::ui::export_plot(plot, path, 100, 100); });
      QVERIFY2(error.startsWith(path + QStringLiteral(": cannot write")), qPrintable(error));
    }
    QVERIFY(QDir(dir.path()).entryList(QDir::Files | QDir::Dirs | QDir::NoDotAndDotDot).isEmpty());
  }

  void writesATableAsCsvWithQuoting() {
    QTemporaryDir dir;
    QTableWidget table(2, 3);
    table.setHorizontalHeaderLabels(
        {QStringLiteral("well"), QStringLiteral("f0_n"), QStringLiteral("note, quoted")});
    const char* cells[2][3] = {{"positive", "0.2", "say \"hi\""},
                               {"negative", "0.3", "two\nlines"}};
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 3; ++c) {
        table.setItem(r, c, new QTableWidgetItem(QString::fromUtf8(cells[r][c])));
      }
    }
    const QString path = dir.filePath(QStringLiteral("table.csv"));
    oscilab::ui::export_table_csv(table, path);
    QCOMPARE(read_all(path), QByteArray("well,f0_n,\"note, quoted\"\n"
                                        "positive,0.2,\"say \"\"hi\"\"\"\n"
                                        "negative,0.3,\"two\nlines\"\n"));
    // A plain model with numbers: DisplayRole text as the view shows it.
    QStandardItemModel model(1, 2);
    model.setHorizontalHeaderLabels({QStringLiteral("a"), QStringLiteral("b")});
    model.setData(model.index(0, 0), 0.25);
    model.setData(model.index(0, 1), 42);
    oscilab::ui::export_table_csv(model, path);
    QCOMPARE(read_all(path), QByteArray("a,b\n0.25,42\n"));
    const QString bad = dir.filePath(QStringLiteral("no/dir/table.csv"));
    QVERIFY(input_error_of([&] {
              oscilab::ui::export_table_csv(model, bad);
            }).startsWith(bad + QStringLiteral(": cannot write")));
  }
};

QTEST_MAIN(PlotExportTest)
#include "plot_export_test.moc"

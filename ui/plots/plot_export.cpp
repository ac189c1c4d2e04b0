#include "ui/plots/plot_export.h"

#include <QAbstractItemModel>
#include <QFile>
#include <QFileInfo>
#include <QSaveFile>
#include <QStringList>
#include <QSvgGenerator>
#include <QTabWidget>
#include <QTableWidget>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "daq/recording/temporary_file.h"
#include "ui/plots/clipping_paint_device.h"

namespace oscilab::ui {
namespace {

[[noreturn]] void fail(const QString& path, const QString& why) {
  throw InputError((path + ": " + why).toStdString());
}

// Draws the plot into an SVG file through QCustomPlot's vectorised painter.
bool write_svg(QCustomPlot& plot, const QString& file_name, int width_px, int height_px) {
  QFile file(file_name);
  if (!file.open(QIODevice::WriteOnly)) return false;
  QSvgGenerator generator;
  generator.setOutputDevice(&file);
  generator.setSize(QSize(width_px, height_px));
  generator.setViewBox(QRect(0, 0, width_px, height_px));
  generator.setTitle(plot.windowTitle().isEmpty() ? QStringLiteral("Oscilab plot")
                                                  : plot.windowTitle());
  generator.setDescription(QStringLiteral("Exported by Oscilab"));
  QPainter svg;
  if (!svg.begin(&generator)) return false;
  // The generator ignores clipping: the device cuts what crosses an axis rect itself.
  ClippingPaintDevice clipped(svg, QSize(width_px, height_px));
  QCPPainter painter;
  if (!painter.begin(&clipped)) return false;
  painter.setMode(QCPPainter::pmVectorized);
  plot.toPainter(&painter, width_px, height_px);
  painter.end();
  svg.end();
  return file.flush() && file.error() == QFileDevice::NoError;
}

QString csv_field(QString text) {
  if (text.contains(QLatin1Char(',')) || text.contains(QLatin1Char('"')) ||
      text.contains(QLatin1Char('\n')) || text.contains(QLatin1Char('\r'))) {
    text.replace(QStringLiteral("\""), QStringLiteral("\"\""));
    return QLatin1Char('"') + text + QLatin1Char('"');
  }
  return text;
}

// Lower-case ASCII words of `text` joined by "-", at most eight; "" when it has none.
QString slug(const QString& text) {
  const QString plain = text.normalized(QString::NormalizationForm_KD).toLower();
  QStringList words;
  QString word;
  for (const QChar c : plain + QLatin1Char(' ')) {
    if (c.unicode() < 128 && c.isLetterOrNumber()) {
      word += c;
    } else if (c.category() != QChar::Mark_NonSpacing && !word.isEmpty()) {
      words << word;
      word.clear();
    }
  }
  return words.mid(0, 8).join(QLatin1Char('-'));
}

QString title_of(const QCustomPlot& plot) {
  for (int i = 0; i < plot.plotLayout()->elementCount(); ++i) {
    if (auto* title = qobject_cast<QCPTextElement*>(plot.plotLayout()->elementAt(i))) {
      QString text = title->text();
      return text.remove(QChar(0x2026));  // an elided title keeps its first words
    }
  }
  return {};
}

// The label of the tab `plot` sits in, at any depth (a scroll area inside a tab).
QString tab_of(const QWidget& plot) {
  for (const QWidget* w = &plot; w && !w->isWindow(); w = w->parentWidget()) {
    const QWidget* stack = w->parentWidget();
    auto* tabs = stack ? qobject_cast<const QTabWidget*>(stack->parentWidget()) : nullptr;
    if (tabs && tabs->indexOf(const_cast<QWidget*>(w)) >= 0) {
      return tabs->tabText(tabs->indexOf(const_cast<QWidget*>(w))).remove(QLatin1Char('&'));
    }
  }
  return {};
}

}  // namespace

QString plot_file_name(const QCustomPlot& plot) {
  QString name = plot.objectName();
  if (name.endsWith(QLatin1String("_plot"))) name.chop(5);
  for (const QString& candidate :
       {name, title_of(plot), tab_of(plot),
        plot.yAxis && plot.xAxis && !plot.yAxis->label().isEmpty()
            ? plot.yAxis->label() + QStringLiteral(" vs ") + plot.xAxis->label()
            : QString()}) {
    if (const QString file = slug(candidate); !file.isEmpty()) return file;
  }
  return QStringLiteral("plot");
}

void export_plot(QCustomPlot& plot, const QString& path, int width_px, int height_px) {
  const QString extension = QFileInfo(path).suffix().toLower();
  if (extension != QLatin1String("png") && extension != QLatin1String("pdf") &&
      extension != QLatin1String("svg")) {
    fail(path, QStringLiteral("unknown image format \"%1\": use .png, .pdf or .svg")
                   .arg(QFileInfo(path).suffix()));
  }
  if (width_px < 0 || height_px < 0) {
    fail(path, QStringLiteral("invalid size %1 x %2 px").arg(width_px).arg(height_px));
  }
  const int width = width_px > 0 ? width_px : plot.width();
  const int height = height_px > 0 ? height_px : plot.height();
  if (width <= 0 || height <= 0) fail(path, QStringLiteral("the plot has no size"));

  daq::TemporaryFile file(path.toStdString());
  const QString temporary = QString::fromStdString(file.path());
  bool written = false;
  if (extension == QLatin1String("png")) {
    written = plot.savePng(temporary, width, height);
  } else if (extension == QLatin1String("pdf")) {
    written = plot.savePdf(temporary, width, height, QCP::epAllowCosmetic,
                           QStringLiteral("Oscilab"), plot.windowTitle());
  } else {
    written = write_svg(plot, temporary, width, height);
  }
  // QPdfWriter reports no error; an empty or missing file is a failed write.
  if (!written || QFileInfo(temporary).size() == 0) fail(path, QStringLiteral("cannot write"));
  file.commit();
}

void export_table_csv(const QAbstractItemModel& model, const QString& path) {
  QSaveFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Text)) {
    fail(path, QStringLiteral("cannot write: ") + file.errorString());
  }
  const int rows = model.rowCount();
  const int columns = model.columnCount();
  QStringList fields;
  for (int c = 0; c < columns; ++c) {
    fields << csv_field(model.headerData(c, Qt::Horizontal, Qt::DisplayRole).toString());
  }
  QByteArray text = fields.join(QLatin1Char(',')).toUtf8() + '\n';
  for (int r = 0; r < rows; ++r) {
    fields.clear();
    for (int c = 0; c < columns; ++c) {
      fields << csv_field(model.data(model.index(r, c), Qt::DisplayRole).toString());
    }
    text += fields.join(QLatin1Char(',')).toUtf8() + '\n';
  }
  if (file.write(text) != text.size() || !file.commit()) {
    fail(path, QStringLiteral("write failed: ") + file.errorString());
  }
}

void export_table_csv(const QTableWidget& table, const QString& path) {
  export_table_csv(*table.model(), path);
}

}  // namespace oscilab::ui

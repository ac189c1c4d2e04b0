#include "ui/plot_export.h"

#include <QAbstractItemModel>
#include <QFile>
#include <QFileInfo>
#include <QSaveFile>
#include <QStringList>
#include <QSvgGenerator>
#include <QTableWidget>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "daq/recording/temporary_file.h"

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
  QCPPainter painter;
  if (!painter.begin(&generator)) return false;
  painter.setMode(QCPPainter::pmVectorized);
  plot.toPainter(&painter, width_px, height_px);
  painter.end();
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

}  // namespace

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

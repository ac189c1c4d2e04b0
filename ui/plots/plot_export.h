#pragma once

#include <QString>

class QAbstractItemModel;
class QCustomPlot;
class QTableWidget;

namespace oscilab::ui {

/// Saves `plot` as an image whose format follows the extension of `path` (case-insensitive):
/// `.png` (raster, QCustomPlot::savePng), `.pdf` (vector, QCustomPlot::savePdf) or `.svg`
/// (vector, QSvgGenerator). A size of 0 takes the plot's current width or height in pixels; the
/// PNG then has exactly that many pixels, the PDF page and the SVG view box that many points or
/// user units. Needs a QApplication (the offscreen platform is enough).
///
/// The file is written under a temporary name beside `path` and renamed into place, so a failure
/// leaves no half-written file. Throws oscilab::InputError naming the file for an unknown
/// extension or a failed write: call it from a slot inside a try block (nothing may throw out of
/// a Qt slot).
void export_plot(QCustomPlot& plot, const QString& path, int width_px = 0, int height_px = 0);

/// A file name (without extension) after what `plot` shows, for the export dialog to propose:
/// its object name without "_plot" (loop_plot: "loop"), else its title row, else the label of the
/// tab it sits in, else its axes' labels ("z-mm-vs-t-s"), else "plot"; lower-case ASCII words
/// joined by "-" (at most eight), symbols spelled in ASCII where Unicode has a form (z₊: z+).
QString plot_file_name(const QCustomPlot& plot);

/// Writes a table as CSV (RFC 4180 quoting, UTF-8, "\n" line ends): a header row of the model's
/// horizontal header labels, then every row's DisplayRole text; a field holding a comma, a quote
/// or a line break is quoted, with quotes doubled. Atomic like export_plot; throws
/// oscilab::InputError naming the file when it cannot be written.
void export_table_csv(const QAbstractItemModel& model, const QString& path);
/// The same for a QTableWidget's model.
void export_table_csv(const QTableWidget& table, const QString& path);

}  // namespace oscilab::ui

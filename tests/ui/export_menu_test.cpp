// GUI test of File ▸ Export and the plots' context menu on the bundled samples under the
// offscreen platform: each export writes a file that an independent reader accepts (QImage for
// the PNG, the CSV header of the level table, matio for the MAT-files, the dataset lines of the
// UFF), and a failed export is reported, not thrown.
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <QAction>
#include <QApplication>
#include <QContextMenuEvent>
#include <QHeaderView>
#include <QImage>
#include <QMenu>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <matio.h>
#include <qcustomplot.h>

#include "daq/recording/recording.h"
#include "ui/export_menu.h"
#include "ui/main_window.h"
#include "ui/review/level_table.h"
#include "ui/review/record_view.h"
#include "ui/review/review_view.h"

using oscilab::ui::ExportMenu;
using oscilab::ui::MainWindow;

namespace {

const QString kSamples = QStringLiteral(OSCILAB_SOURCE_DIR "/samples/");
constexpr int kTimeoutMs = 60000;  // the analysis of both samples takes ~1 s; CI is slower

struct MatClose {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct MatVarFree {
  void operator()(matvar_t* variable) const { Mat_VarFree(variable); }
};

// Elements of a numeric MAT variable read by matio (-1: missing or not double).
long matio_length(const QString& path, const char* name) {
  std::unique_ptr<mat_t, MatClose> mat(Mat_Open(path.toStdString().c_str(), MAT_ACC_RDONLY));
  if (!mat) return -1;
  std::unique_ptr<matvar_t, MatVarFree> variable(Mat_VarRead(mat.get(), name));
  if (!variable || variable->class_type != MAT_C_DOUBLE) return -1;
  return static_cast<long>(variable->nbytes / sizeof(double));
}

std::vector<std::string> lines_of(const QString& path) {
  std::ifstream in(path.toStdString());
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Waits for the export's end and returns (message, ok).
std::pair<QString, bool> finished_of(QSignalSpy& spy) {
  if (spy.isEmpty() && !spy.wait(kTimeoutMs)) return {"timed out", false};
  const QList<QVariant> args = spy.takeFirst();
  return {args.at(0).toString(), args.at(1).toBool()};
}

}  // namespace

class ExportMenuTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void initTestCase() {
    window_ = std::make_unique<MainWindow>();
    window_->set_interactive_errors(false);
    window_->resize(1400, 900);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
    QSignalSpy analysed(window_.get(), &MainWindow::analysis_finished);
    QCOMPARE(window_->open_recordings(
                 {kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"}),
             2);
    QVERIFY(analysed.wait(kTimeoutMs));
    QVERIFY(window_->export_menu() != nullptr);
  }

  void cleanupTestCase() { window_.reset(); }

  void fileMenuHasTheExports() {
    ExportMenu* exports = window_->export_menu();
    QStringList texts;
    for (QAction* a : exports->menu()->actions()) {
      if (!a->isSeparator()) texts << a->text();
    }
    QCOMPARE(texts, QStringList({"&Plot as PNG/SVG/PDF\u2026", "Level &table as CSV\u2026",
                                 "Recording as &MATLAB .mat\u2026", "Recording as &UFF 58\u2026",
                                 "&EDC table as .mat\u2026"}));
    QCOMPARE(exports->menu()->menuAction()->text(), QString("&Export"));
  }

  void plotExportsAsPngOfItsSize() {
    ExportMenu* exports = window_->export_menu();
    QCustomPlot* plot = exports->plot_to_export();
    QVERIFY(plot != nullptr && plot->isVisible());
    QTemporaryDir dir;
    const QString path = dir.filePath("plot.png");
    QSignalSpy finished(exports, &ExportMenu::export_finished);
    QVERIFY(exports->export_plot(path));
    QVERIFY(finished_of(finished).second);
    const QImage image(path);
    QCOMPARE(image.size(), plot->size());  // export_plot: the size on screen, in pixels
  }

  void levelTableExportsAsCsv() {
    ExportMenu* exports = window_->export_menu();
    QTemporaryDir dir;
    const QString path = dir.filePath("levels.csv");
    QVERIFY(exports->export_level_table(path));
    const auto lines = lines_of(path);
    auto* table = window_->review_view()->level_table();
    QString header;
    for (int c = 0; c < table->columnCount(); ++c) {
      header += (c ? "," : "") + table->horizontalHeaderItem(c)->text();
    }
    QVERIFY(!lines.empty());
    QCOMPARE(QString::fromStdString(lines.front()), header);
    QCOMPARE(lines.size(), std::size_t{1 + 52});  // 26 levels per sample
  }

  void recordingExportsAsMatAndUff() {
    ExportMenu* exports = window_->export_menu();
    const oscilab::daq::OpenedRecording* shown = window_->record_view()->recording();
    QVERIFY(shown != nullptr);
    QTemporaryDir dir;
    QSignalSpy finished(exports, &ExportMenu::export_finished);

    const QString mat = dir.filePath("recording.mat");
    QVERIFY(exports->export_recording_mat(mat));
    auto [message, ok] = finished_of(finished);
    QVERIFY2(ok, qPrintable(message));
    QCOMPARE(matio_length(mat, "t_s"), static_cast<long>(shown->sample_count()));
    QCOMPARE(matio_length(mat, "sample_rate_hz"), 1L);

    const QString uff = dir.filePath("recording.uff");
    QVERIFY(exports->export_recording_uff(uff));
    std::tie(message, ok) = finished_of(finished);
    QVERIFY2(ok, qPrintable(message));
    // Datasets are delimited by "    -1" lines, each opened by its number in I6: one 164 (units)
    // and one 58 per channel.
    const auto lines = lines_of(uff);
    int units = 0, functions = 0;
    for (std::size_t i = 1; i < lines.size(); ++i) {
      if (lines[i - 1] != "    -1") continue;
      if (lines[i] == "   164") ++units;
      if (lines[i] == "    58") ++functions;
    }
    QCOMPARE(units, 1);
    QCOMPARE(functions, static_cast<int>(shown->sidecar.channels.size()));
  }

  void edcTableExportsAsMat() {
    ExportMenu* exports = window_->export_menu();
    QTemporaryDir dir;
    QSignalSpy finished(exports, &ExportMenu::export_finished);
    const QString path = dir.filePath("edc.mat");
    QVERIFY(exports->export_edc_mat(path));
    const auto [message, ok] = finished_of(finished);
    QVERIFY2(ok, qPrintable(message));
    QCOMPARE(matio_length(path, "f0_n"), 52L);
    QCOMPARE(matio_length(path, "edc_mean_j"), 52L);
  }

  void failedExportIsReportedNotThrown() {
    ExportMenu* exports = window_->export_menu();
    QSignalSpy finished(exports, &ExportMenu::export_finished);
    QSignalSpy errors(window_.get(), &MainWindow::error_reported);
    const QString path = "/proc/oscilab-no-such-dir/edc.mat";
    QVERIFY(exports->export_edc_mat(path));  // started: the worker finds the folder missing
    const auto [message, ok] = finished_of(finished);
    QVERIFY(!ok);
    QVERIFY2(message.contains(path), qPrintable(message));
    QCOMPARE(errors.count(), 1);
    QVERIFY(!exports->export_plot("plot.bmp"));  // an unknown format, at once
    QVERIFY(std::get<0>(finished_of(finished)).contains("plot.bmp"));
  }

  void rightClickOnAnyPlotOffersExport() {
    QCustomPlot* plot = window_->record_view()->plot();
    QVERIFY(plot->isVisible());
    const QPoint at(plot->width() / 2, plot->height() / 2);
    QContextMenuEvent event(QContextMenuEvent::Mouse, at, plot->mapToGlobal(at));
    QApplication::sendEvent(plot, &event);
    QTRY_VERIFY_WITH_TIMEOUT(QApplication::activePopupWidget() != nullptr, kTimeoutMs);
    auto* menu = qobject_cast<QMenu*>(QApplication::activePopupWidget());
    QVERIFY(menu != nullptr);
    QCOMPARE(menu->actions().size(), 1);
    QCOMPARE(menu->actions().front()->text(), QString("Export plot\u2026"));
    menu->close();
    QCOMPARE(window_->export_menu()->plot_to_export(), plot);  // the plot used last
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

QTEST_MAIN(ExportMenuTest)
#include "export_menu_test.moc"

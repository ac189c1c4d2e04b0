// GUI test of File ▸ Open for a file without a sidecar, under the offscreen platform: the
// mapping dialog starts from the drafted sidecar, turns the form into a sidecar with the
// sidecar's own checks (a bad value keeps the dialog open and says why), and the main window
// saves the answer as the file's sidecar and opens the file; a cancelled mapping opens nothing
// and writes nothing.
#include <cmath>
#include <fstream>
#include <optional>
#include <string>

#include <QApplication>
#include <QComboBox>
#include <QFileInfo>
#include <QLabel>
#include <QLineEdit>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include "daq/recording/recording.h"
#include "ui/main_window.h"
#include "ui/review/channel_mapping_dialog.h"

using oscilab::daq::FileContents;
using oscilab::daq::FileSignal;
using oscilab::ui::ChannelMappingDialog;
using oscilab::ui::MainWindow;

namespace {

FileContents logger_contents() {
  FileContents contents;
  contents.container = "test";
  contents.file_signals = {FileSignal{"logger/laser", 400, 1, "mm/s", 200.0, "float64", {}},
                           FileSignal{"logger/table", 400, 1, "m/s\u00b2", 200.0, "float32", {}}};
  return contents;
}

// A CSV with a t_s column at 512 Hz and two signals, 2 s long, and no sidecar.
QString write_csv(const QTemporaryDir& dir) {
  const QString path = dir.filePath("logger.csv");
  std::ofstream out(path.toStdString());
  out << "t_s,acc,pos\n";
  for (int i = 0; i < 1024; ++i) {
    const double t = i / 512.0;
    out << t << ',' << std::sin(2 * M_PI * 9 * t) << ',' << 1e-3 * std::cos(2 * M_PI * 9 * t)
        << '\n';
  }
  return path;
}

}  // namespace

class ChannelMappingDialogTest : public QObject {
  Q_OBJECT

 private slots:
  void starts_from_the_draft() {
    ChannelMappingDialog dialog("run.tdms", logger_contents());
    QCOMPARE(dialog.base_row().signal->currentData().toString(), QString("logger/table"));
    QCOMPARE(dialog.base_row().unit->currentText(), QString("m/s^2"));
    QCOMPARE(dialog.mass_row().signal->currentData().toString(), QString("logger/laser"));
    QCOMPARE(dialog.mass_row().quantity->currentText(), QString("velocity"));
    QCOMPARE(dialog.rate_edit()->text(), QString("200"));
    const std::optional<oscilab::daq::Sidecar> sidecar = dialog.sidecar();
    QVERIFY2(sidecar.has_value(), qPrintable(dialog.problem()));
    QCOMPARE(sidecar->channels[0].source, std::string("logger/table"));
    QCOMPARE(sidecar->channels[1].unit, std::string("mm/s"));
    QVERIFY(!sidecar->mass_kg.has_value());
  }

  void turns_the_form_into_a_sidecar() {
    ChannelMappingDialog dialog("run.tdms", logger_contents());
    dialog.mass_row().quantity->setCurrentText("displacement");
    dialog.mass_row().unit->setCurrentText("um");
    dialog.mass_row().scale->setText("2.5e-3");
    dialog.mass_edit()->setText("0.26");
    const std::optional<oscilab::daq::Sidecar> sidecar = dialog.sidecar();
    QVERIFY2(sidecar.has_value(), qPrintable(dialog.problem()));
    QCOMPARE(sidecar->channels[1].quantity, oscilab::daq::Quantity::Displacement);
    QCOMPARE(sidecar->channels[1].unit, std::string("um"));
    QCOMPARE(sidecar->channels[1].scale, 2.5e-3);
    QCOMPARE(*sidecar->mass_kg, 0.26);
  }

  void a_bad_value_keeps_the_dialog_open_and_says_why() {
    ChannelMappingDialog dialog("run.tdms", logger_contents());
    dialog.rate_edit()->setText("fast");
    QVERIFY(!dialog.sidecar().has_value());
    QVERIFY2(dialog.problem().contains("sample_rate_hz"), qPrintable(dialog.problem()));
    dialog.accept();
    QVERIFY(dialog.result() != QDialog::Accepted);
    QCOMPARE(dialog.findChild<QLabel*>("problem")->text(), dialog.problem());
    dialog.rate_edit()->setText("200");
    dialog.base_row().scale->setText("0");
    QVERIFY(!dialog.sidecar().has_value());
    QVERIFY2(dialog.problem().contains("scale: must not be zero"), qPrintable(dialog.problem()));
  }

  void the_main_window_saves_the_answer_and_opens_the_file() {
    QTemporaryDir dir;
    const QString path = write_csv(dir);
    MainWindow window;
    int asked = 0;
    window.set_mapping_asker([&](const QString& asked_path, const FileContents& contents) {
      ++asked;
      ChannelMappingDialog dialog(asked_path, contents);
      dialog.rate_edit()->setText("512");
      dialog.base_row().signal->setCurrentIndex(dialog.base_row().signal->findData("acc"));
      dialog.mass_row().signal->setCurrentIndex(dialog.mass_row().signal->findData("pos"));
      dialog.mass_row().quantity->setCurrentText("displacement");
      dialog.mass_row().unit->setCurrentText("m");
      return dialog.sidecar();
    });
    QVERIFY(window.open_recording(path));
    QCOMPARE(asked, 1);
    const QString sidecar_path = dir.filePath("logger.json");
    QVERIFY(QFileInfo::exists(sidecar_path));
    const oscilab::daq::Recording recording = oscilab::daq::read_recording(path.toStdString());
    QCOMPARE(recording.sample_count(), Eigen::Index(1024));
    QCOMPARE(recording.sidecar.channels[0].name, std::string("acc"));
    QCOMPARE(window.opened_paths(), QStringList{QFileInfo(path).absoluteFilePath()});
    // Opened again: the sidecar now says it all, nothing is asked.
    QVERIFY(window.open_recording(path));
    QCOMPARE(asked, 1);
  }

  void a_cancelled_mapping_opens_nothing_and_writes_nothing() {
    QTemporaryDir dir;
    const QString path = write_csv(dir);
    MainWindow window;
    window.set_interactive_errors(false);
    window.set_mapping_asker([](const QString&, const FileContents&) { return std::nullopt; });
    QSignalSpy errors(&window, &MainWindow::error_reported);
    QVERIFY(!window.open_recording(path));
    QCOMPARE(errors.count(), 1);
    QVERIFY2(errors.front().front().toString().contains("no sidecar says what its signals are"),
             qPrintable(errors.front().front().toString()));
    QVERIFY(!QFileInfo::exists(dir.filePath("logger.json")));
    QVERIFY(window.opened_paths().isEmpty());
  }
};

QTEST_MAIN(ChannelMappingDialogTest)
#include "channel_mapping_dialog_test.moc"

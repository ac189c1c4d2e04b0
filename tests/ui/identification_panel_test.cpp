// GUI test of the fit and diagnosis panel (issues 6 and 9), driving the real widgets under the
// offscreen platform on the bundled samples: a fit fills the parameter table and the EDC plot, a
// running fit cancels, a diagnosis of the paper's own model says none, a bad recording is
// reported, and File ▸ Open feeds the panel.
#include <QComboBox>
#include <QLabel>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTest>

#include <qcustomplot.h>

#include "ui/identification_panel.h"
#include "ui/main_window.h"

using oscilab::ui::IdentificationPanel;
using oscilab::ui::MainWindow;

namespace {

const std::string kSamples = std::string(OSCILAB_SOURCE_DIR) + "/samples/";

}  // namespace

class IdentificationPanelTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void fitFillsTableAndPlot() {
    IdentificationPanel panel;
    panel.set_recordings({kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"});
    panel.set_fit_settings("ga", 2000, 6, 1);  // 6 + 5 evaluations: the widgets, not the fit
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    QTest::mouseClick(panel.fit_button(), Qt::LeftButton);
    QVERIFY(panel.busy());
    QVERIFY(!panel.fit_button()->isEnabled());
    QVERIFY(panel.cancel_button()->isEnabled());
    QVERIFY(done.wait(120000));
    QVERIFY(!panel.busy());
    QVERIFY2(panel.status_label()->text().startsWith("Fit: 11 evaluations"),
             qPrintable(panel.status_label()->text()));
    QCOMPARE(panel.parameter_table()->rowCount(), 6);
    QCOMPARE(panel.parameter_table()->item(0, 0)->text(), QString("fd_zminus_n"));
    QCOMPARE(panel.parameter_table()->item(5, 0)->text(), QString("c_ns_m"));
    // Two wells × (measured, model), 26 levels each.
    QCOMPARE(panel.edc_plot()->graphCount(), 4);
    QCOMPARE(panel.edc_plot()->graph(0)->data()->size(), 26);
    QCOMPARE(panel.edc_plot()->graph(1)->data()->size(), 26);
    // The convergence curve: the GA's best after generation 0 and after generation 1.
    QCOMPARE(panel.convergence_plot()->graph(0)->data()->size(), 2);
    QVERIFY(panel.convergence_plot()->graph(0)->data()->at(1)->value <=
            panel.convergence_plot()->graph(0)->data()->at(0)->value);
    QVERIFY(panel.fit_button()->isEnabled());
  }

  void cancelStopsARunningFit() {
    IdentificationPanel panel;
    panel.set_recordings({kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"});
    panel.set_fit_settings("cmaes", 100000, 100, 20);
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    panel.start_fit();
    QTest::qWait(500);
    QVERIFY(panel.busy());
    QTest::mouseClick(panel.cancel_button(), Qt::LeftButton);
    QVERIFY(done.wait(20000));
    // Points reached the curve while the fit ran (queued from the worker, ≤ 20 a second).
    QVERIFY(!panel.convergence_plot()->graph(0)->data()->isEmpty());
    QCOMPARE(done.takeFirst().at(0).toString(), QString("Cancelled."));
    QVERIFY(panel.fit_button()->isEnabled());
  }

  void diagnosisOfThePapersOwnModelSaysNone() {
    IdentificationPanel panel;
    panel.set_recordings({kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"});
    panel.set_diagnosis_budget(300, 200);
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    QTest::mouseClick(panel.diagnose_button(), Qt::LeftButton);
    QVERIFY(done.wait(180000));
    QVERIFY2(done.takeFirst().at(0).toString().startsWith("Diagnosis: none"),
             qPrintable(panel.status_label()->text()));
    QVERIFY(panel.verdict_label()->text().contains("Verdict: none"));
    QCOMPARE(panel.residual_plot()->graphCount(), 4);  // baseline and final, both wells
    QCOMPARE(panel.tabs()->currentIndex(), 2);
  }

  void badRecordingIsReportedNotFatal() {
    IdentificationPanel panel;
    panel.set_recordings({kSamples + "no_such_file.flac"});
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    panel.start_fit();
    QVERIFY(done.wait(20000));
    const QString message = done.takeFirst().at(0).toString();
    QVERIFY2(message.startsWith("Error: ") && message.contains("no_such_file.flac"),
             qPrintable(message));
    QVERIFY(panel.fit_button()->isEnabled());
  }

  void openedRecordingsFeedThePanel() {
    MainWindow window;
    window.set_interactive_errors(false);
    QVERIFY(window.open_recording(QString::fromStdString(kSamples + "stepped_positive.flac")));
    QVERIFY(window.open_recording(QString::fromStdString(kSamples + "stepped_negative.flac")));
    QVERIFY(window.open_recording(QString::fromStdString(kSamples + "stepped_positive.flac")));
    QCOMPARE(window.identification_panel()->recordings().size(), std::size_t{2});  // no repeats
  }
};

QTEST_MAIN(IdentificationPanelTest)
#include "identification_panel_test.moc"

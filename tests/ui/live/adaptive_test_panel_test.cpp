// GUI test of the Live tab's adaptive test (AdaptiveTestPanel) under the offscreen platform, on
// a test small enough for the suite (two pilot levels per well, one candidate, short fits, no
// final diagnosis): the settings become the loop's options and a bad one is refused in one line;
// with Auto off the operator's Skip brings a new proposal without a level and Stop ends the test
// with the folder written; in auto mode it runs to its end and the strip chart holds one point
// per decision for every hypothesis; a cancel while a proposal waits ends it.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTest>

#include <qcustomplot.h>
#include <nlohmann/json.hpp>

#include "analysis/model/reference_models.h"
#include "daq/recording/json_file.h"
#include "tests/analysis/design/small_adaptive_test.h"
#include "ui/live/adaptive_test_panel.h"
#include "ui/live/live_monitor.h"

using oscilab::analysis::ProposalAnswer;
using oscilab::ui::AdaptiveTestJob;
using oscilab::ui::AdaptiveTestPanel;

namespace {

std::string fresh_folder(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() /
                      ("oscilab_adaptive_panel_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  return folder.string();
}

// The rig hides a quadratic damping (c2 = 6 N s²/m²); the loop is the unit suite's small one.
AdaptiveTestJob::Request small_request(const std::string& folder, bool auto_mode) {
  AdaptiveTestJob::Request r;
  r.rig_truth = oscilab::testing::quadratic_damping_truth();
  r.schedule = {6.0, 1.0, 2.5};
  r.seed = 7;
  r.folder = folder;
  r.auto_mode = auto_mode;
  r.options = oscilab::testing::small_adaptive_test_options();
  return r;
}

int lines_of(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) ++n;
  return n;
}

}  // namespace

class AdaptiveTestPanelTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void settingsBecomeTheLoopsOptionsAndABadOneIsRefusedInOneLine();
  void theOperatorSkipsAProposalThenStopsTheTest();
  void anAutoTestRunsToItsEndAndChartsEveryDecision();
  void aCancelWhileAProposalWaitsEndsTheTest();
  void theLiveTabHoldsTheAdaptiveTest();
};

void AdaptiveTestPanelTest::settingsBecomeTheLoopsOptionsAndABadOneIsRefusedInOneLine() {
  AdaptiveTestPanel panel;
  panel.wells_box()->setCurrentIndex(1);  // positive
  panel.budget_box()->setValue(300.0);
  panel.effects_edit()->setText(QStringLiteral("quadratic-damping, cubic-damping"));
  const AdaptiveTestJob::Request r = panel.request();
  QVERIFY(r.options.settings.positive_well);
  QVERIFY(!r.options.settings.negative_well);
  QCOMPARE(r.options.stop.budget_s, 300.0);
  QCOMPARE(r.options.hypotheses.effects.size(), std::size_t{2});
  QCOMPARE(r.options.hypotheses.effects[1], std::string("cubic-damping"));
  QVERIFY(r.auto_mode);
  QCOMPARE(r.rig_truth.mass_kg(), oscilab::analysis::paper_model().mass_kg());

  // An unknown effect, a rig truth that is no file, no folder: not started, one line each.
  panel.effects_edit()->setText(QStringLiteral("quadratic-damping,drag"));
  QVERIFY(!panel.start());
  QVERIFY2(panel.verdict_label()->text().startsWith("Not started: Effects"),
           qPrintable(panel.verdict_label()->text()));
  QVERIFY(panel.verdict_label()->text().contains("drag"));
  panel.effects_edit()->clear();
  panel.rig_truth_edit()->setText(QStringLiteral("/nonexistent/rig.json"));
  QVERIFY(!panel.start());
  QVERIFY2(panel.verdict_label()->text().contains("/nonexistent/rig.json"),
           qPrintable(panel.verdict_label()->text()));
  panel.rig_truth_edit()->setText(QStringLiteral("paper"));
  panel.folder_edit()->clear();
  QVERIFY(!panel.start());
  QVERIFY(panel.verdict_label()->text().contains("Folder"));
  QVERIFY(!panel.running());
}

void AdaptiveTestPanelTest::theOperatorSkipsAProposalThenStopsTheTest() {
  AdaptiveTestPanel panel;
  panel.resize(1000, 560);
  panel.show();
  panel.auto_box()->setChecked(false);
  const std::string folder = fresh_folder("manual");
  QSignalSpy waiting(panel.job(), &AdaptiveTestJob::awaiting_changed);
  QSignalSpy finished(&panel, &AdaptiveTestPanel::test_finished);
  QVERIFY(panel.start(small_request(folder, false)));
  QVERIFY(!panel.run_button()->isEnabled());  // nothing proposed yet

  // The first proposal waits for the operator.
  QTRY_VERIFY_WITH_TIMEOUT(panel.job()->awaiting_answer() && panel.run_button()->isEnabled(),
                           60000);
  QCOMPARE(panel.steps().size(), std::size_t{1});
  QVERIFY(panel.steps()[0].proposed);
  QVERIFY2(panel.proposal_label()->text().startsWith("Next: <b>"),
           qPrintable(panel.proposal_label()->text()));
  QVERIFY(panel.skip_button()->isEnabled() && panel.stop_button()->isEnabled());
  QCOMPARE(panel.weights_table()->rowCount(), 2);  // the baseline and the one candidate
  QCOMPARE(panel.weights_plot()->graphCount(), 2);

  // Skip: a second proposal, somewhere else, with no level run between.
  QTest::mouseClick(panel.skip_button(), Qt::LeftButton);
  QTRY_VERIFY_WITH_TIMEOUT(panel.steps().size() == 2 && panel.job()->awaiting_answer(), 60000);
  const auto& first = panel.steps()[0];
  const auto& second = panel.steps()[1];
  QCOMPARE(second.levels, first.levels);
  QCOMPARE(second.shaker_time_s, first.shaker_time_s);
  QVERIFY(second.proposed);
  QVERIFY(second.proposal.f0_n != first.proposal.f0_n ||
          second.proposal.positive_well != first.proposal.positive_well);

  // Stop: the test ends, the folder holds both decisions and the report says who stopped it.
  QTest::mouseClick(panel.stop_button(), Qt::LeftButton);
  QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 60000);
  QVERIFY(!panel.running());
  QVERIFY(!panel.run_button()->isEnabled());
  QVERIFY2(panel.verdict_label()->text().startsWith("Done: 4 levels (0 adaptive)"),
           qPrintable(panel.verdict_label()->text()));
  QCOMPARE(lines_of(folder + "/decisions.jsonl"), 2);
  const nlohmann::json report = oscilab::daq::read_json_file(folder + "/report.json", 1 << 22);
  QCOMPARE(
      report["adaptive_test"]["stop_reason"].get<std::string>().rfind("stopped by the operator", 0),
      std::size_t{0});
  QCOMPARE(report["records"].size(), std::size_t{2});  // the two pilots
  QVERIFY(waiting.count() >= 4);                       // two waits, each begun and ended
  std::filesystem::remove_all(folder);
}

void AdaptiveTestPanelTest::anAutoTestRunsToItsEndAndChartsEveryDecision() {
  AdaptiveTestPanel panel;
  const std::string folder = fresh_folder("auto");
  QSignalSpy finished(&panel, &AdaptiveTestPanel::test_finished);
  QVERIFY(panel.start(small_request(folder, true)));
  QVERIFY(!panel.start(small_request(folder, true)));  // one at a time
  QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 120000);
  const auto& steps = panel.steps();
  QVERIFY(steps.size() >= 2);  // after the pilot and after each adaptive level
  QVERIFY(steps.back().decision.stop);
  for (int h = 0; h < panel.weights_plot()->graphCount(); ++h) {
    QCOMPARE(panel.weights_plot()->graph(h)->dataCount(), static_cast<int>(steps.size()));
  }
  // The table's rows, the leader first, carry the last decision's weights.
  const double top = panel.weights_table()->item(0, 1)->text().toDouble();
  const double next = panel.weights_table()->item(1, 1)->text().toDouble();
  QVERIFY(top >= next);
  QVERIFY(std::abs(top + next - 1.0) < 2e-4);  // two weights printed to four decimals
  QCOMPARE(lines_of(folder + "/decisions.jsonl"), static_cast<int>(steps.size()));
  QVERIFY(std::filesystem::exists(folder + "/report.json"));
  QVERIFY2(panel.verdict_label()->text().startsWith("Done: "),
           qPrintable(panel.verdict_label()->text()));
  std::filesystem::remove_all(folder);
}

void AdaptiveTestPanelTest::aCancelWhileAProposalWaitsEndsTheTest() {
  AdaptiveTestPanel panel;
  const std::string folder = fresh_folder("cancel");
  QSignalSpy finished(&panel, &AdaptiveTestPanel::test_finished);
  QVERIFY(panel.start(small_request(folder, false)));
  QTRY_VERIFY_WITH_TIMEOUT(panel.job()->awaiting_answer(), 60000);
  panel.cancel();
  QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 10000);
  QVERIFY2(panel.verdict_label()->text().startsWith("Cancelled after"),
           qPrintable(panel.verdict_label()->text()));
  QCOMPARE(lines_of(folder + "/decisions.jsonl"), 1);  // what was decided stays
  std::filesystem::remove_all(folder);
}

void AdaptiveTestPanelTest::theLiveTabHoldsTheAdaptiveTest() {
  oscilab::ui::LiveMonitor monitor;
  QVERIFY(monitor.adaptive_test() != nullptr);
  QCOMPARE(monitor.views()->count(), 2);
  QCOMPARE(monitor.views()->tabText(1), QStringLiteral("Adaptive test"));
  QCOMPARE(monitor.views()->widget(1), static_cast<QWidget*>(monitor.adaptive_test()));
}

QTEST_MAIN(AdaptiveTestPanelTest)
#include "adaptive_test_panel_test.moc"

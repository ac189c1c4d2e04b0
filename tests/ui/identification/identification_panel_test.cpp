// GUI test of the fit and diagnosis panel, driving the real widgets under the
// offscreen platform on the bundled samples: a fit fills the parameter table and the EDC plot, a
// running fit draws the best model's EDC as it goes and a cancelled one says so (while the
// recordings are analysed and during the search), a diagnosis of the paper's own model says none
// and draws its residual and missing-energy figures, a bad recording is reported, and File ▸ Open
// feeds the panel. How fast a cancel comes back and how smooth the event loop stays during a fit
// are measured by tests/bench/fit_panel_benchmark.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <vector>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSignalSpy>
#include <QSpinBox>
#include <QSplitter>
#include <QTableWidget>
#include <QTest>

#include <qcustomplot.h>

#include "analysis/identification/edc_objective.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/model/reference_models.h"
#include "daq/recording/campaign_reader.h"

#include "ui/identification/identification_panel.h"
#include "ui/main_window.h"

using oscilab::ui::FitPreview;
using oscilab::ui::IdentificationPanel;
using oscilab::ui::MainWindow;

namespace {

const std::string kSamples = std::string(OSCILAB_SOURCE_DIR) + "/samples/";

void set_samples(IdentificationPanel& panel) {
  panel.set_recordings({kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"});
}

}  // namespace

class IdentificationPanelTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void fitFillsTableAndPlot() {
    IdentificationPanel panel;
    panel.set_recordings({kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"});
    panel.set_fit_settings("ga", 2000, 6, 1);  // 6 + 5 evaluations: the widgets, not the fit
    // The stiffness is identified by default (ten parameters, settled after the search); the
    // model's K(z) held keeps the six friction parameters of Table 3 and the GA's count exact.
    auto* stiffness = panel.findChild<QComboBox*>("stiffness");
    QVERIFY(stiffness != nullptr);
    QCOMPARE(stiffness->currentData().toString(), QString("identified"));
    stiffness->setCurrentIndex(stiffness->findData("model"));
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    QTest::mouseClick(panel.fit_button(), Qt::LeftButton);
    QVERIFY(panel.busy());
    QVERIFY(!panel.fit_button()->isEnabled());
    QVERIFY(panel.cancel_button()->isEnabled());
    QVERIFY(done.wait(120000));
    QVERIFY(!panel.busy());
    QCOMPARE(panel.findChild<QProgressBar*>("job_progress")->value(), 1000);  // finished: full
    QVERIFY2(panel.status_label()->text().startsWith("Fit: 11 evaluations"),
             qPrintable(panel.status_label()->text()));
    QCOMPARE(panel.parameter_table()->rowCount(), 6);
    // Table 3's symbols with units; the FIT JSON's key beside.
    QCOMPARE(panel.parameter_table()->item(0, 0)->text(), QString("f_d(z\u208b*) [N]"));
    QCOMPARE(panel.parameter_table()->item(0, 0)->data(Qt::UserRole).toString(),
             QString("fd_zminus_n"));
    QCOMPARE(panel.parameter_table()->item(5, 0)->text(), QString("c [N s/m]"));
    QCOMPARE(panel.parameter_table()->item(5, 0)->data(Qt::UserRole).toString(), QString("c_ns_m"));
    // Two wells × (measured, model), 26 levels each.
    QCOMPARE(panel.edc_plot()->graphCount(), 4);
    QCOMPARE(panel.edc_plot()->graph(0)->data()->size(), 26);
    QCOMPARE(panel.edc_plot()->graph(1)->data()->size(), 26);
    // The axis starts at 0 and leaves room above every point and its ±3σ bar (none on the frame).
    const QCPRange edc_axis = panel.edc_plot()->yAxis->range();
    QCOMPARE(edc_axis.lower, 0.0);
    double top_mj = 0.0;
    for (int g = 0; g < panel.edc_plot()->plottableCount(); ++g) {
      bool found = false;
      const QCPRange values = panel.edc_plot()->plottable(g)->getValueRange(found);
      if (found) top_mj = std::max(top_mj, values.upper);
    }
    QVERIFY(top_mj > 0.0);
    QVERIFY2(edc_axis.upper >= 1.05 * top_mj, qPrintable(QString::number(edc_axis.upper)));
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
    // Points reach the curve while the fit runs (queued from the worker, ≤ 20 a second).
    QTRY_VERIFY_WITH_TIMEOUT(!panel.convergence_plot()->graph(0)->data()->isEmpty(), 60000);
    QVERIFY(panel.busy());
    QTest::mouseClick(panel.cancel_button(), Qt::LeftButton);
    QVERIFY(done.wait(60000));
    QCOMPARE(done.takeFirst().at(0).toString(), QString("Cancelled."));
    QVERIFY(panel.fit_button()->isEnabled());
    // The bar keeps the fraction the fit reached: full is for a fit that finished.
    auto* bar = panel.findChild<QProgressBar*>("job_progress");
    QVERIFY(bar != nullptr);
    QVERIFY2(bar->value() < bar->maximum(), qPrintable(QString::number(bar->value())));
  }

  void livePreviewDrawsTheBestModelWhileFitting() {
    IdentificationPanel panel;
    set_samples(panel);
    panel.set_fit_settings("cmaes", 100000, 100, 20);
    // Emission times on the worker (direct connection: this runs on the worker thread).
    std::mutex mutex;
    std::vector<std::chrono::steady_clock::time_point> emitted;
    std::shared_ptr<const FitPreview> last;
    connect(
        &panel, &IdentificationPanel::fit_preview, &panel,
        [&](std::shared_ptr<const FitPreview> preview) {
          const std::lock_guard<std::mutex> lock(mutex);
          emitted.push_back(std::chrono::steady_clock::now());
          last = std::move(preview);
        },
        Qt::DirectConnection);
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    panel.start_fit();
    // The EDC tab shows "best so far" curves before the fit ends: measured and model per well.
    QTRY_VERIFY_WITH_TIMEOUT(panel.edc_plot()->graphCount() == 4 &&
                                 panel.edc_plot()->graph(1)->name().contains("best so far"),
                             60000);
    QTRY_VERIFY_WITH_TIMEOUT(
        [&] {
          const std::lock_guard<std::mutex> lock(mutex);
          return emitted.size() >= 4;
        }(),
        60000);
    panel.cancel();
    QVERIFY(done.wait(60000));
    const std::lock_guard<std::mutex> lock(mutex);
    // At most 5 a second: consecutive emissions ≥ 200 ms apart (same clock, so no tolerance).
    for (std::size_t i = 1; i < emitted.size(); ++i) {
      QVERIFY(emitted[i] - emitted[i - 1] >= std::chrono::milliseconds(200));
    }
    // The preview is the model of its θ: the objective's own evaluation of that θ (the path the
    // fit takes) gives the same S^mod at every level, to rounding.
    QVERIFY(last && last->objective);
    const auto check = last->objective->evaluate(last->theta);
    QCOMPARE(last->edc_mod_j.size(), check.edc_mod_j.size());
    for (std::size_t g = 0; g < check.edc_mod_j.size(); ++g) {
      QCOMPARE(last->edc_mod_j[g].size(), std::size_t{26});
      for (std::size_t i = 0; i < check.edc_mod_j[g].size(); ++i) {
        QVERIFY(std::abs(last->edc_mod_j[g][i] - check.edc_mod_j[g][i]) <=
                1e-12 * std::abs(check.edc_mod_j[g][i]));
      }
    }
    std::printf("live preview: %zu EDC curves of the best model drawn during the fit\n",
                emitted.size());
  }

  // A click on Cancel before the search has started (the recordings are still being analysed)
  // ends the job as cancelled, with the buttons back; no fit result is kept.
  void cancelWhileTheRecordingsAreAnalysed() {
    IdentificationPanel panel;
    set_samples(panel);
    panel.set_fit_settings("cmaes", 100000, 100, 20);
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    panel.start_fit();
    QVERIFY(panel.busy());
    QVERIFY(panel.convergence_plot()->graph(0)->data()->isEmpty());  // no search point yet
    QTest::mouseClick(panel.cancel_button(), Qt::LeftButton);
    QVERIFY(done.wait(60000));
    QCOMPARE(done.takeFirst().at(0).toString(), QString("Cancelled."));
    QVERIFY(!panel.busy());
    QVERIFY(panel.fit_button()->isEnabled());
    QCOMPARE(panel.parameter_table()->rowCount(), 0);
    auto* bar = panel.findChild<QProgressBar*>("job_progress");
    QVERIFY(bar != nullptr);
    QVERIFY2(bar->value() < bar->maximum(), qPrintable(QString::number(bar->value())));
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
    // figures::residual_figure, one axis rect per well: the baseline's and the final model's
    // residuals and the ±3σ band (two curves: it breaks at NaN between +3σ and −3σ).
    QCOMPARE(panel.residual_plot()->axisRectCount(), 2);
    QCOMPARE(panel.residual_plot()->plottableCount(), 2 * (1 + 1 + 2));
    // figures::missing_energy_figure on a page of its own, as `diagnose` writes missing_energy.png:
    // one panel, a series each for the levels the baseline under- and over-predicts, together a
    // point for every level of both wells (none is predicted exactly), at log10 |Z1| of a
    // response between 1 µm and 10 cm and log10 of a missing energy below 1 J.
    QCustomPlot* missing = panel.missing_energy_plot();
    QCOMPARE(panel.tabs()->tabText(panel.tabs()->indexOf(missing)), QString("Missing energy"));
    QCOMPARE(missing->axisRectCount(), 1);
    QCOMPARE(missing->plottableCount(), 2);
    QCOMPARE(missing->axisRect(0)->axis(QCPAxis::atBottom)->label(),
             QString("log10 amplitude |Z1| [m]"));
    int points = 0;
    for (int p = 0; p < missing->plottableCount(); ++p) {
      auto* curve = qobject_cast<QCPCurve*>(missing->plottable(p));
      QVERIFY(curve != nullptr);
      for (auto it = curve->data()->constBegin(); it != curve->data()->constEnd(); ++it) {
        QVERIFY2(it->key > -6.0 && it->key < -1.0, qPrintable(QString::number(it->key)));
        QVERIFY2(std::isfinite(it->value) && it->value < 0.0,
                 qPrintable(QString::number(it->value)));
        ++points;
      }
    }
    QCOMPARE(points, panel.budget_table()->rowCount());
    QCOMPARE(panel.tabs()->tabText(panel.tabs()->currentIndex()), QString("Diagnosis"));
  }

  // The presliding samples hide a Dahl element the paper's form lacks: the diagnosis names it, the
  // evidence table lists every candidate with its outcome, and the σ-budget tab every level.
  void diagnosisNamesTheHiddenPreslidingWithItsEvidence() {
    IdentificationPanel panel;
    panel.set_recordings(
        {kSamples + "presliding_positive.flac", kSamples + "presliding_negative.flac"});
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    panel.start_diagnosis();
    QVERIFY(done.wait(300000));
    QVERIFY2(done.takeFirst().at(0).toString().startsWith("Diagnosis: presliding-hysteresis"),
             qPrintable(panel.status_label()->text()));
    QVERIFY(panel.verdict_label()->text().contains("Supported by: edc"));
    QTableWidget* table = panel.step_table();
    // The candidates of the paper's form with its stiffness identified (the default), at least:
    // Stribeck, Coulomb, quadratic and cubic damping, presliding as an added element and as the
    // friction's regime, and the quintic stiffness (the quadratic and cubic are the form's own).
    QVERIFY2(table->rowCount() >= 7, qPrintable(QString::number(table->rowCount())));
    int accepted = 0;
    for (int row = 0; row < table->rowCount(); ++row) {
      if (table->item(row, 2)->text() == "accepted") {
        ++accepted;
        QCOMPARE(table->item(row, 1)->text(), QString("presliding-hysteresis"));
      } else {
        QVERIFY2(table->item(row, 2)->text().startsWith("rejected") ||
                     table->item(row, 2)->text().startsWith("not solved"),
                 qPrintable(table->item(row, 2)->text()));
      }
    }
    QCOMPARE(accepted, 1);
    QCOMPARE(panel.budget_table()->rowCount(), 52);  // every level of both wells
  }

  // The panel offers what `oscilab-cli fit` offers (base model, stiffness source, harmonics, a
  // fixed model-error floor) and fits through the same sequence (analysis::prepare_fit): the
  // objective it fitted is the one prepare_fit makes headless from the same choices, and its χ²
  // at the fitted θ is the same number.
  void fitUsesTheChosenSetupThroughTheSharedSequence() {
    IdentificationPanel panel;
    set_samples(panel);
    panel.set_fit_settings("ga", 2000, 6, 1);
    auto* stiffness = panel.findChild<QComboBox*>("stiffness");
    auto* harmonics = panel.findChild<QSpinBox*>("harmonics");
    auto* model_error = panel.findChild<QDoubleSpinBox*>("model_error");
    QVERIFY(stiffness && harmonics && model_error);
    stiffness->setCurrentIndex(stiffness->findData("rfs"));
    harmonics->setValue(5);
    model_error->setValue(2.0);  // a fixed 2 % floor instead of the σ budget
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    panel.start_fit();
    QVERIFY(done.wait(120000));
    QVERIFY2(done.takeFirst().at(0).toString().startsWith("Fit: "),
             qPrintable(panel.status_label()->text()));
    const auto objective = panel.fit_objective();
    QVERIFY(objective != nullptr);
    QCOMPARE(objective->settings().hbm.harmonics, 5);
    QCOMPARE(objective->settings().model_error_rel, 0.02);

    oscilab::analysis::FitSetup setup;
    setup.stiffness = oscilab::analysis::StiffnessSource::Rfs;
    setup.cost.hbm.harmonics = 5;
    setup.cost.model_error_rel = 0.02;
    const auto campaign = oscilab::daq::analyze_recordings(
        {kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"}, {}, {});
    const oscilab::analysis::PreparedFit headless = oscilab::analysis::prepare_fit(campaign, setup);
    const Eigen::VectorXd& theta = panel.fit_result()->theta;
    QCOMPARE(headless.objective->evaluate(theta).weighted_cost,
             objective->evaluate(theta).weighted_cost);
    // The same base model: the recordings' mass and the RFS cubic in place of Table 1's K(z).
    QCOMPARE(QString::fromStdString(objective->form().base().to_json().dump()),
             QString::fromStdString(headless.objective->form().base().to_json().dump()));
    QVERIFY(QString::fromStdString(oscilab::analysis::paper_model().to_json().dump()) !=
            QString::fromStdString(objective->form().base().to_json().dump()));
  }

  // The form offers no GA budget the analysis (and `oscilab-cli fit`) refuses: population ×
  // (generations + 1) stays within kMaxFitEvaluations whichever box moves last.
  void gaBudgetStaysWithinWhatAFitAccepts() {
    IdentificationPanel panel;
    auto* population = panel.findChild<QSpinBox*>("population");
    auto* generations = panel.findChild<QSpinBox*>("generations");
    QVERIFY(population && generations);
    const auto within = [&] {
      return static_cast<long>(population->value()) * (generations->value() + 1) <=
             oscilab::analysis::kMaxFitEvaluations;
    };
    population->setValue(population->maximum());
    generations->setValue(generations->maximum());
    QCOMPARE(population->value(), 10000);
    QCOMPARE(generations->value(), 999);
    QVERIFY(within());
    population->setValue(2);
    generations->setValue(generations->maximum());
    QCOMPARE(generations->value(), 10000);
    population->setValue(population->maximum());
    QCOMPARE(population->value(), 999);
    QVERIFY(within());
  }

  // The set-up above the results gets its whole height once the panel is tall enough, also when
  // the panel grows after it was first laid out short (a window resized to a large screen).
  void setUpGetsItsHeightAsThePanelGrows() {
    IdentificationPanel panel;
    panel.resize(420, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    auto* splitter = panel.findChild<QSplitter*>("fit_splitter");
    QVERIFY(splitter != nullptr);
    // What the set-up's contents ask for (its scroll area's own hint stops at 24 lines of text).
    auto* setup = qobject_cast<QScrollArea*>(splitter->widget(0));
    QVERIFY(setup != nullptr && setup->widget() != nullptr);
    const int wanted = setup->widget()->sizeHint().height();
    QTRY_VERIFY(splitter->sizes().at(0) < wanted);  // a third of 600 px: the set-up scrolls
    panel.resize(420, 1400);
    QTRY_COMPARE(splitter->sizes().at(0), wanted);
  }

  void badRecordingIsReportedNotFatal() {
    IdentificationPanel panel;
    panel.set_recordings({kSamples + "no_such_file.flac"});
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    panel.start_fit();
    QVERIFY(done.wait(60000));
    const QString message = done.takeFirst().at(0).toString();
    QVERIFY2(message.startsWith("Error: ") && message.contains("no_such_file.flac"),
             qPrintable(message));
    QVERIFY(panel.fit_button()->isEnabled());
    auto* bar = panel.findChild<QProgressBar*>("job_progress");
    QVERIFY(bar != nullptr && bar->value() < bar->maximum());  // a failed job is not full
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

// GUI test of what the fit panel offers after a fit, on the bundled samples under the
// offscreen platform: the figures dialog (Figs. 13–16), "Export results…" (FIT JSON, PNG, CSV),
// and the HBM branch and bifurcation map dialogs of the fitted model, each checked against an
// independent reader or a direct call of the analysis core with the same settings.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include <QComboBox>
#include <QDir>
#include <QFile>
#include <QImage>
#include <QLabel>
#include <QPushButton>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>

#include <qcustomplot.h>
#include <nlohmann/json.hpp>

#include "analysis/hbm/continuation.h"
#include "analysis/identification/fit_report.h"
#include "analysis/simulation/bifurcation_map.h"
#include "ui/identification/figure_dialog.h"
#include "ui/identification/identification_panel.h"
#include "ui/identification/response_dialog.h"

using oscilab::ui::IdentificationPanel;
using oscilab::ui::ResponseDialog;
namespace analysis = oscilab::analysis;

namespace {

const std::string kSamples = std::string(OSCILAB_SOURCE_DIR) + "/samples/";

// The first line of a text file.
std::string first_line(const QString& path) {
  std::ifstream in(path.toStdString());
  std::string line;
  std::getline(in, line);
  return line;
}

int line_count(const QString& path) {
  std::ifstream in(path.toStdString());
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// The continuation the dialog should run, written out here from the settings it shows (the
// range of the paper's Fig. 11, 0.1 to 3.7 N, which covers the samples' 0.2 to 2.7 N; H = 7 of
// the fit's harmonic balance; the CLI's largest step 0.1), not taken from the dialog.
analysis::ContinuationOptions expected_options(bool positive, double freq_hz) {
  analysis::ContinuationOptions o;
  o.start = 0.1;
  o.end = 3.7;
  o.freq_hz = freq_hz;
  o.positive_well = positive;
  o.hbm.harmonics = 7;
  o.max_step = 0.1;
  o.initial_step = std::min(o.initial_step, o.max_step);
  return o;
}

// Relative agreement of two results of the same deterministic computation: identical up to the
// order of floating-point operations, so 1e-12 is already generous.
bool same(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(1e-30, std::abs(b)); }

}  // namespace

class FitResultsTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void initTestCase() {
    panel_ = new IdentificationPanel;
    panel_->set_recordings(
        {kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"});
    // A short CMA-ES fit (the figures and dialogs need a θ, not the best one), of the six
    // friction parameters of Table 3 that Figs. 13–16 show: the model's K(z) held (the form
    // identifies the stiffness by default, four more parameters).
    panel_->set_fit_settings("cmaes", 200, 100, 20);
    auto* stiffness = panel_->findChild<QComboBox*>("stiffness");
    QVERIFY(stiffness != nullptr);
    stiffness->setCurrentIndex(stiffness->findData("model"));
    QVERIFY(!panel_->figures_button()->isEnabled());
    QVERIFY(!panel_->branch_button()->isEnabled());
    QSignalSpy done(panel_, &IdentificationPanel::job_finished);
    panel_->start_fit();
    QVERIFY(done.wait(120000));
    QVERIFY2(panel_->fit_result() != nullptr, qPrintable(panel_->status_label()->text()));
    QVERIFY(panel_->figures_button()->isEnabled());
    QVERIFY(panel_->export_button()->isEnabled());
    QVERIFY(panel_->branch_button()->isEnabled());
    QVERIFY(panel_->map_button()->isEnabled());
  }

  void cleanupTestCase() { delete panel_; }

  void figuresDialogShowsFigs13To16() {
    QSignalSpy shown(panel_, &IdentificationPanel::figures_shown);
    QTest::mouseClick(panel_->figures_button(), Qt::LeftButton);
    QVERIFY(shown.wait(60000));
    auto* dialog = panel_->figures_dialog();
    QVERIFY(dialog != nullptr && dialog->isVisible());
    // EDC, convergence, friction, cost slices, and the sensitivity of both wells.
    QCOMPARE(dialog->tabs()->count(), 6);
    QCOMPARE(dialog->tabs()->tabText(3), QString("Cost slices (Fig. 13)"));
    // Fig. 13: one panel per parameter of θ (6), each with its axes labelled.
    QCustomPlot* slices = dialog->plot(3);
    QCOMPARE(slices->axisRectCount(), 6);
    for (QCPAxisRect* rect : slices->axisRects()) {
      QCOMPARE(rect->axis(QCPAxis::atLeft)->label(), QString("log10 chi2"));
      QVERIFY(!rect->axis(QCPAxis::atBottom)->label().isEmpty());
    }
    // Fig. 15 in the dialog: the model's EDC is the fit's S^mod (mJ).
    QCustomPlot* edc = dialog->plot(0);
    QCOMPARE(edc->axisRect(0)->axis(QCPAxis::atBottom)->label(),
             QString("forcing amplitude f0 [N]"));
    QCOMPARE(edc->axisRect(0)->axis(QCPAxis::atLeft)->label(), QString("EDC [mJ]"));
    dialog->close();
  }

  void exportWritesFitJsonFiguresAndTables() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString out = dir.filePath("results");
    QSignalSpy finished(panel_, &IdentificationPanel::export_finished);
    panel_->export_results(out);
    QVERIFY(finished.wait(60000));
    const QList<QVariant> args = finished.takeFirst();
    QVERIFY2(args.at(1).toBool(), qPrintable(args.at(0).toString()));

    // The FIT JSON: what `merge` reads from a CLI fit, with θ as the panel shows it.
    std::ifstream json_file((out + "/fit.json").toStdString());
    QVERIFY(json_file.good());
    const nlohmann::json json = nlohmann::json::parse(json_file);
    const analysis::FitSummary summary = analysis::read_fit_summary(json, "fit.json");
    const analysis::FitResult& fit = *panel_->fit_result();
    QCOMPARE(summary.parameters.size(), fit.names.size());
    for (std::size_t i = 0; i < fit.names.size(); ++i) {  // a JSON object: sorted by name
      const auto named = std::find_if(summary.parameters.begin(), summary.parameters.end(),
                                      [&](const auto& p) { return p.first == fit.names[i]; });
      QVERIFY2(named != summary.parameters.end(), fit.names[i].c_str());
      QVERIFY(same(named->second, fit.theta(static_cast<int>(i))));
    }
    QCOMPARE(json.at("format").get<std::string>(), std::string("oscilab-fit/1"));
    QVERIFY(json.contains("notes"));

    // PNGs at the figures' sizes: 1000 px wide, panels × panel height + 30 px of title.
    const QImage edc(out + "/edc_fit.png");
    QCOMPARE(edc.width(), 1000);
    QCOMPARE(edc.height(), 2 * 380 + 30);
    const QImage slices(out + "/cost_slices.png");
    QCOMPARE(slices.height(), 6 * 220 + 30);
    for (const char* name : {"convergence.png", "friction.png", "sensitivity_positive.png",
                             "sensitivity_negative.png"}) {
      QVERIFY2(!QImage(out + "/" + name).isNull(), name);
    }
    // The CSV tables of `oscilab-cli fit --figures`, headers as there.
    QCOMPARE(first_line(out + "/edc_fit.csv"),
             std::string("well,f0_n,edc_mes_j,edc_std_j,cycles,edc_mod_j,deviation_pct"));
    QCOMPARE(line_count(out + "/edc_fit.csv"), 1 + 52);  // 26 levels per well
    QCOMPARE(first_line(out + "/cost_slices.csv"),
             std::string("parameter,value,weighted_cost,cost_j"));
    QCOMPARE(line_count(out + "/cost_slices.csv"), 1 + 6 * 21);
    QCOMPARE(first_line(out + "/sensitivity.csv"), std::string("parameter,factor,well,f0_n,edc_j"));
    QCOMPARE(first_line(out + "/convergence.csv"), std::string("evaluations,best_weighted_cost"));
    QCOMPARE(first_line(out + "/friction.csv"), std::string("z_m,fd_n"));
  }

  void exportIntoAnUnwritablePlaceIsReported() {
    QSignalSpy finished(panel_, &IdentificationPanel::export_finished);
    panel_->export_results("/proc/oscilab-no-such-dir");
    QVERIFY(finished.count() == 1 || finished.wait(60000));
    const QList<QVariant> args = finished.takeFirst();
    QVERIFY(!args.at(1).toBool());
    QVERIFY2(args.at(0).toString().contains("/proc/oscilab-no-such-dir"),
             qPrintable(args.at(0).toString()));
  }

  void branchDialogMatchesADirectContinuation() {
    QPointer<ResponseDialog> dialog = panel_->open_branch_dialog();
    QVERIFY(dialog);
    QSignalSpy computed(dialog.data(), &ResponseDialog::computed);
    QVERIFY(computed.wait(60000));
    QCOMPARE(dialog->branches().size(), std::size_t{2});

    const analysis::Model model =
        panel_->fit_objective()->form().build(panel_->fit_result()->theta);
    const auto& groups = panel_->fit_objective()->data().groups;
    QCOMPARE(groups.size(), std::size_t{2});
    for (std::size_t w = 0; w < groups.size(); ++w) {
      const analysis::Branch direct = analysis::continue_branch(
          model, expected_options(groups[w].positive_well, groups[w].freq_hz));
      const analysis::Branch& shown = dialog->branches()[w];
      QCOMPARE(shown.positive_well, groups[w].positive_well);
      QCOMPARE(shown.points.size(), direct.points.size());
      QCOMPARE(shown.events.size(), direct.events.size());
      for (std::size_t i = 0; i < std::min<std::size_t>(20, direct.points.size()); ++i) {
        QVERIFY(same(shown.points[i].f0_n, direct.points[i].f0_n));
        QVERIFY(same(shown.points[i].measures.amp_m, direct.points[i].measures.amp_m));
        QVERIFY(same(shown.points[i].measures.edc_j, direct.points[i].measures.edc_j));
        QCOMPARE(shown.points[i].floquet.stable, direct.points[i].floquet.stable);
      }
    }
    // Fig. 11 style: amplitude and EDC panels, with units.
    QCOMPARE(dialog->plot()->axisRectCount(), 2);
    QCOMPARE(dialog->plot()->axisRect(1)->axis(QCPAxis::atLeft)->label(),
             QString("energy dissipated per cycle [mJ]"));

    QTemporaryDir dir;
    const QString csv = dir.filePath("branches.csv");
    QVERIFY(dialog->export_csv(csv));
    // docs/contracts.md §3 columns first, the well column last (two wells).
    const std::string header = first_line(csv);
    QVERIFY2(header.rfind("f0_n,amp_m,z1_abs_m,phase_rad,edc_j,stable", 0) == 0, header.c_str());
    QVERIFY(header.size() > 5 && header.substr(header.size() - 5) == ",well");
    QCOMPARE(line_count(csv), 1 + static_cast<int>(dialog->branches()[0].points.size() +
                                                   dialog->branches()[1].points.size()));
    dialog->close();
  }

  void mapDialogMatchesADirectMap() {
    QPointer<ResponseDialog> dialog = panel_->open_map_dialog();
    QVERIFY(dialog);
    QSignalSpy computed(dialog.data(), &ResponseDialog::computed);
    // The dialog starts with the default map (seconds); cancel it, then a small one.
    QVERIFY(dialog->busy());
    QTest::mouseClick(dialog->cancel_button(), Qt::LeftButton);
    QVERIFY(computed.wait(60000));
    QCOMPARE(computed.takeFirst().at(0).toString(), QString("Cancelled."));
    QVERIFY(!dialog->export_button()->isEnabled());
    dialog->set_f0_range(0.5, 2.5);
    dialog->set_map_settings(0.5, 20, 4);
    QTest::mouseClick(dialog->compute_button(), Qt::LeftButton);
    QVERIFY(computed.wait(60000));
    QVERIFY(dialog->export_button()->isEnabled());

    analysis::BifurcationMapOptions o;  // written out, not read from the dialog
    o.freq_hz = panel_->fit_objective()->data().groups.front().freq_hz;
    o.start_n = 0.5;
    o.end_n = 2.5;
    o.step_n = 0.5;
    o.hold_periods = 20;
    o.sampled_periods = 4;
    const analysis::Model model =
        panel_->fit_objective()->form().build(panel_->fit_result()->theta);
    const analysis::BifurcationMap direct = analysis::bifurcation_map(model, o);
    const analysis::BifurcationMap& shown = dialog->map();
    QCOMPARE(shown.rows.size(), direct.rows.size());
    QCOMPARE(shown.rows.size(), std::size_t{2 * 5 * 4});  // wells × levels × sampled periods
    for (std::size_t i = 0; i < direct.rows.size(); ++i) {
      QCOMPARE(shown.rows[i].positive_well, direct.rows[i].positive_well);
      QCOMPARE(shown.rows[i].period, direct.rows[i].period);
      QVERIFY(same(shown.rows[i].f0_n, direct.rows[i].f0_n));
      QVERIFY(same(shown.rows[i].z_m, direct.rows[i].z_m));
    }
    // Fig. 17 style: a Poincaré section per well, then the HBM amplitude.
    QCOMPARE(dialog->plot()->axisRectCount(), 3);
    QCOMPARE(dialog->plot()->axisRect(0)->axis(QCPAxis::atLeft)->label(),
             QString("z at t = nT [mm]"));

    QTemporaryDir dir;
    const QString csv = dir.filePath("map.csv");
    QVERIFY(dialog->export_csv(csv));
    QCOMPARE(first_line(csv), std::string("f0_n,well,z_m,period"));
    QCOMPARE(line_count(csv), 1 + static_cast<int>(direct.rows.size()));
    dialog->close();
  }

 private:
  IdentificationPanel* panel_ = nullptr;
};

QTEST_MAIN(FitResultsTest)
#include "fit_results_test.moc"

// GUI test of the record review, driving the real widgets under the offscreen platform
// on the bundled samples: both recordings open and are analysed on a worker thread, the level
// table lists every level with the EDCs of an independent offline analysis, a selected level
// draws its Fig. 9 loop (whose area is its EDC) and moves the shared cursor, annotations are
// added, and a session saved and opened in a fresh window brings all of it back; a bad session
// file is reported and changes nothing.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <QApplication>
#include <QDir>
#include <QDockWidget>
#include <QFile>
#include <QLabel>
#include <QListWidget>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>

#include <qcustomplot.h>

#include "daq/recording/campaign_reader.h"
#include "ui/live/live_monitor.h"
#include "ui/main_window.h"
#include "ui/plots/well_colours.h"
#include "ui/review/level_table.h"
#include "ui/review/record_view.h"
#include "ui/review/review_model.h"
#include "ui/review/review_view.h"

using oscilab::analysis::LevelResult;
using oscilab::ui::LevelKey;
using oscilab::ui::LevelTable;
using oscilab::ui::MainWindow;
using oscilab::ui::ReviewView;

namespace {

const QString kSamples = QStringLiteral(OSCILAB_SOURCE_DIR "/samples/");
const QString kPositive = kSamples + "stepped_positive.flac";
const QString kNegative = kSamples + "stepped_negative.flac";
constexpr double kRateHz = 512.0;  // the samples' rate
constexpr double kFreqHz = 9.0;    // their excitation frequency
// The analysis of two 262 s records takes seconds; this bounds a hung worker, not the speed.
constexpr int kAnalysisTimeoutMs = 180000;

// The level of `well` closest to f0 = `f0_n` in the independent analysis.
LevelKey level_near(const oscilab::analysis::CampaignAnalysis& campaign,
                    oscilab::analysis::Well well, double f0_n) {
  LevelKey best;
  double distance = INFINITY;
  for (std::size_t r = 0; r < campaign.records.size(); ++r) {
    const auto& levels = campaign.records[r].levels;
    for (std::size_t l = 0; l < levels.size(); ++l) {
      if (levels[l].well == well && std::abs(levels[l].f0_n - f0_n) < distance) {
        distance = std::abs(levels[l].f0_n - f0_n);
        best = {int(r), int(l)};
      }
    }
  }
  return best;
}

// ∮ f dz of a drawn curve, back in SI from the plot's display units.
double curve_area_j(const QCPCurve* curve, double z_si_per_unit, double f_si_per_unit) {
  double area = 0.0;
  const auto& data = *curve->data();
  for (int i = 1; i < data.size(); ++i) {
    area +=
        0.5 * (data.at(i)->value + data.at(i - 1)->value) * (data.at(i)->key - data.at(i - 1)->key);
  }
  return area * z_si_per_unit * f_si_per_unit;
}

void click(QWidget* widget, QPoint at, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  QTest::mouseClick(widget, Qt::LeftButton, modifiers, at);
}

}  // namespace

class ReviewViewTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void initTestCase() {
    QVERIFY(temporary_.isValid());
    // The independent oracle: the offline analysis as the CLI runs it, from the files.
    expected_ = oscilab::daq::analyze_recordings({kPositive.toStdString(), kNegative.toStdString()},
                                                 {}, {});
    QCOMPARE(expected_.records.size(), std::size_t{2});
    window_ = std::make_unique<MainWindow>();
    window_->set_interactive_errors(false);
    window_->resize(1400, 900);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
  }
  void cleanupTestCase() { window_.reset(); }

  void centralWidgetIsTabsWithTheReviewFirst() {
    QTabWidget* tabs = window_->central_tabs();
    QVERIFY(tabs != nullptr);
    QCOMPARE(window_->centralWidget(), tabs);
    QCOMPARE(tabs->widget(0), window_->review_view());
    QCOMPARE(tabs->tabText(0), QString("Review"));
    QCOMPARE(window_->record_view(), window_->review_view()->record_view());
  }

  void opensBothSamplesAndAnalysesThemOnAWorker() {
    QSignalSpy analysed(window_.get(), &MainWindow::analysis_finished);
    QCOMPARE(window_->open_recordings({kPositive, kNegative}), 2);
    // open returned before the analysis ran: the UI thread does not wait for it.
    QVERIFY(window_->analysis_running());
    QCOMPARE(window_->review_view()->level_table()->rowCount(), 0);
    QVERIFY(analysed.wait(kAnalysisTimeoutMs));
    QVERIFY(!window_->analysis_running());
    QCOMPARE(window_->opened_paths(), QStringList({QFileInfo(kPositive).absoluteFilePath(),
                                                   QFileInfo(kNegative).absoluteFilePath()}));
    // The first is shown.
    QVERIFY(window_->windowTitle().startsWith("stepped_positive.flac"));
    auto* status = window_->findChild<QLabel*>("analysis_status");
    QVERIFY(status != nullptr);
    QVERIFY2(status->text().startsWith("Analysis: 2 records"), qPrintable(status->text()));
  }

  void levelTableHasEveryLevelWithTheOfflineEdcs() {
    LevelTable* table = window_->review_view()->level_table();
    int levels = 0;
    for (const auto& record : expected_.records) levels += int(record.levels.size());
    QVERIFY(levels >= 50);  // 26 levels a well: 0.2 → 2.7 N in 0.1 N steps
    QCOMPARE(table->rowCount(), levels);
    std::set<LevelKey> seen;
    for (int row = 0; row < table->rowCount(); ++row) {
      const LevelKey key = table->key_at(row);
      QVERIFY(seen.insert(key).second);  // each level once
      QVERIFY(key.record >= 0 && key.record < 2);
      const auto& record = expected_.records[std::size_t(key.record)];
      QVERIFY(key.level >= 0 && std::size_t(key.level) < record.levels.size());
      const LevelResult& level = record.levels[std::size_t(key.level)];
      QCOMPARE(table->item(row, LevelTable::kRecord)->text(), QString::fromStdString(record.name));
      QCOMPARE(table->item(row, LevelTable::kWell)->text(),
               QString::fromStdString(to_string(level.well)));
      QCOMPARE(table->item(row, LevelTable::kFlags)->text(), QString::fromStdString(level.flags()));
      QCOMPARE(table->item(row, LevelTable::kCycles)->text(), QString::number(level.cycles));
      // The same computation on the same samples: equal up to the last bits of the FFTs.
      const auto value = [&](int column) {
        return table->item(row, column)->data(LevelTable::kValueRole).toDouble();
      };
      QVERIFY(std::abs(value(LevelTable::kF0) - level.f0_n) <= 1e-12 * level.f0_n);
      QVERIFY(std::abs(value(LevelTable::kEdcMean) - level.edc_mean_j) <= 1e-12 * level.edc_mean_j);
      QVERIFY(std::abs(value(LevelTable::kEdcStd) - level.edc_std_j) <= 1e-9 * level.edc_mean_j);
      QCOMPARE(table->item(row, LevelTable::kEdcMean)->text(),
               QString::number(1e3 * level.edc_mean_j, 'f', 4));
    }
    // Until a header is clicked, the analysis's order: record by record, level by level.
    for (int row = 1; row < table->rowCount(); ++row) {
      QVERIFY(table->key_at(row - 1) < table->key_at(row));
    }
    // Sortable: by EDC, ascending.
    table->sortItems(LevelTable::kEdcMean, Qt::AscendingOrder);
    for (int row = 1; row < table->rowCount(); ++row) {
      QVERIFY(table->item(row, LevelTable::kEdcMean)->data(LevelTable::kValueRole).toDouble() >=
              table->item(row - 1, LevelTable::kEdcMean)->data(LevelTable::kValueRole).toDouble());
    }
  }

  // At first look (nothing selected) the loop pane is not empty: each well's usable levels with
  // the lowest, middle and highest f0, blue and orange, named by their f0.
  void theLoopPaneShowsEachWellsLevelsBeforeAnySelection() {
    ReviewView* review = window_->review_view();
    review->select_levels({}, false);
    QCustomPlot* loop_plot = review->loop_plot();
    std::vector<QString> expected_names;
    for (const auto well : {oscilab::analysis::Well::Positive, oscilab::analysis::Well::Negative}) {
      std::vector<double> f0;
      for (const auto& record : expected_.records) {
        for (const LevelResult& level : record.levels) {
          if (level.well == well && level.usable()) f0.push_back(level.f0_n);
        }
      }
      QVERIFY(f0.size() >= 3);  // the samples: 26 levels a well, most of them usable
      std::sort(f0.begin(), f0.end());
      for (double value : {f0.front(), f0[f0.size() / 2], f0.back()}) {
        expected_names.push_back(QString("f\u2080 = %1 N").arg(value, 0, 'f', 2));
      }
    }
    QCOMPARE(loop_plot->plottableCount(), int(expected_names.size()));
    for (int i = 0; i < loop_plot->plottableCount(); ++i) {
      QVERIFY2(loop_plot->plottable(i)->name().contains(expected_names[std::size_t(i)]),
               qPrintable(loop_plot->plottable(i)->name()));
    }
    QCOMPARE(loop_plot->plottable(0)->pen().color().rgba(),
             oscilab::ui::well_colour(oscilab::analysis::Well::Positive).rgba());
    QCOMPARE(loop_plot->plottable(3)->pen().color().rgba(),
             oscilab::ui::well_colour(oscilab::analysis::Well::Negative).rgba());
  }

  void selectingALevelDrawsItsLoopAndMovesTheCursor() {
    ReviewView* review = window_->review_view();
    LevelTable* table = review->level_table();
    review->tabs()->setCurrentIndex(ReviewView::kLevelsTab);
    // Fig. 9: 1.3 N, the negative well first (so that the record shown changes).
    const LevelKey negative = level_near(expected_, oscilab::analysis::Well::Negative, 1.3);
    const LevelKey positive = level_near(expected_, oscilab::analysis::Well::Positive, 1.3);
    QVERIFY(negative.valid() && positive.valid());
    const LevelResult& level =
        expected_.records[std::size_t(negative.record)].levels[std::size_t(negative.level)];
    const int row = table->row_of(negative);
    table->scrollToItem(table->item(row, 0));
    click(table->viewport(), table->visualItemRect(table->item(row, LevelTable::kF0)).center());
    QCOMPARE(review->selected_levels(), std::vector<LevelKey>{negative});

    // The record shown is the level's, the window around it and the cursor at its middle.
    QVERIFY(window_->windowTitle().startsWith("stepped_negative.flac"));
    const double mid_s = 0.5 * (level.start_s + level.end_s);
    const std::optional<double> cursor = window_->record_view()->cursor_time();
    QVERIFY(cursor.has_value());
    QCOMPARE(*cursor, std::round(mid_s * kRateHz) / kRateHz);  // snapped to the nearest sample
    QCOMPARE(review->cursor_time(), cursor);
    const auto window = window_->record_view()->time_window();
    const double margin_s = 0.1 * (level.end_s - level.start_s);
    QVERIFY(std::abs(window.start_s - (level.start_s - margin_s)) < 1e-9);
    QVERIFY(std::abs(window.end_s - (level.end_s + margin_s)) < 1e-9);
    QVERIFY(!window_->record_view()->cursor_follows_mouse());  // held at the level
    // The cycle plot follows the time window, its EDC axis over the cycles in view.
    const QCPRange cycle_time = review->cycle_plot()->xAxis->range();
    QVERIFY(std::abs(cycle_time.lower - window.start_s) < 1e-9);
    QVERIFY(std::abs(cycle_time.upper - window.end_s) < 1e-9);
    const QCPRange edc_axis = review->cycle_plot()->yAxis->range();
    QVERIFY(edc_axis.contains(1e3 * level.edc_mean_j));
    QVERIFY(edc_axis.upper < 1e3 * level.edc_mean_j * 2.0);  // fitted (the log axis spans ×1.3²)
    QVERIFY(!window_->cursor_follows_mouse_action()->isChecked());

    // The loop: every sample of the steady cycles, z in mm against f in N.
    QCustomPlot* loop_plot = review->loop_plot();
    QCOMPARE(loop_plot->plottableCount(), 1);
    auto* curve = qobject_cast<QCPCurve*>(loop_plot->plottable(0));
    QVERIFY(curve != nullptr);
    const int first = int(std::ceil(level.start_s * kRateHz - 1e-9));
    const int last = int(std::floor(level.end_s * kRateHz + 1e-9));
    QCOMPARE(curve->data()->size(), last - first + 1);
    QCOMPARE(loop_plot->xAxis->label(), QString("z [mm]"));
    QCOMPARE(loop_plot->yAxis->label(), QString("f = \u2212m d\u00b2b/dt\u00b2 [N]"));
    QCOMPARE(curve->pen().color().rgba(),
             oscilab::ui::well_colour(oscilab::analysis::Well::Negative).rgba());
    // Its z stays inside the level's range of fitted z (the fits' extremes), give or take the
    // laser's noise and the harmonics above the 8th: 2 % of the range.
    const double z_span_mm = 1e3 * (level.z_max_m - level.z_min_m);
    for (const auto& point : *curve->data()) {
      QVERIFY(point.key > 1e3 * level.z_min_m - 0.02 * z_span_mm);
      QVERIFY(point.key < 1e3 * level.z_max_m + 0.02 * z_span_mm);
    }
    // Its area per cycle is the level's EDC (∮ f dz, §4.1), here from the samples rather than the
    // per-cycle harmonic fits. The trapezoid reads a sampled sinusoid's loop low by the factor
    // sinc(ωh) (review_model_test: exact for whole periods), 0.998 at 9 Hz and 512 Hz; what is
    // left is the partial sample intervals at the level's two ends (~1/4700 of the loop each)
    // and sensor noise: measured 4e-5, allowed 2e-3.
    const double omega_h = 2 * std::numbers::pi * kFreqHz / kRateHz;
    const double per_cycle_j = curve_area_j(curve, 1e-3, 1.0) / level.cycles;
    const double expected_j = level.edc_mean_j * std::sin(omega_h) / omega_h;
    QVERIFY2(std::abs(per_cycle_j / expected_j - 1.0) < 2e-3,
             qPrintable(QString("%1 vs %2").arg(per_cycle_j).arg(expected_j)));

    // Ctrl-click the positive well's 1.3 N: both loops, as in Fig. 9, blue and orange.
    const int other = table->row_of(positive);
    table->scrollToItem(table->item(other, 0));
    click(table->viewport(), table->visualItemRect(table->item(other, LevelTable::kF0)).center(),
          Qt::ControlModifier);
    QCOMPARE(loop_plot->plottableCount(), 2);
    QCOMPARE(review->selected_levels().front(), positive);  // the current row first
    QCOMPARE(qobject_cast<QCPCurve*>(loop_plot->plottable(0))->pen().color().rgba(),
             oscilab::ui::well_colour(oscilab::analysis::Well::Positive).rgba());
    QCOMPARE(qobject_cast<QCPCurve*>(loop_plot->plottable(1))->pen().color().rgba(),
             oscilab::ui::well_colour(oscilab::analysis::Well::Negative).rgba());
    QVERIFY(window_->windowTitle().startsWith("stepped_positive.flac"));
  }

  void aClickInATimePlotMovesTheSharedCursorAndHoldsIt() {
    ReviewView* review = window_->review_view();
    auto* view = window_->record_view();
    window_->cursor_follows_mouse_action()->setChecked(true);
    QVERIFY(view->cursor_follows_mouse());
    view->plot()->replot();  // lays the axis rects out, as a paint would
    QCPAxisRect* rect = view->channel_rect(1);
    QCPAxis* time_axis = rect->axis(QCPAxis::atBottom);
    const oscilab::ui::TimeWindow window = view->time_window();
    const double t_s = window.start_s + 0.25 * window.width_s();
    const QPoint at(int(std::lround(time_axis->coordToPixel(t_s))), rect->rect().center().y());
    QSignalSpy moved(review, &ReviewView::cursor_moved);
    click(view->plot(), at);
    QVERIFY(review->cursor_time().has_value());
    // The click's pixel to the nearest sample: within half a pixel and half a sample.
    const double pixel_s = window.width_s() / rect->width();
    QVERIFY(std::abs(*review->cursor_time() - t_s) <= 0.5 * pixel_s + 0.5 / kRateHz + 1e-12);
    QVERIFY(!moved.isEmpty());
    QCOMPARE(moved.back().front().toDouble(), *review->cursor_time());
    QVERIFY(!view->cursor_follows_mouse());
    // Held: the mouse moving away does not move it.
    const double held = *review->cursor_time();
    QMouseEvent move(QEvent::MouseMove, QPointF(at + QPoint(80, 0)),
                     view->plot()->mapToGlobal(QPointF(at + QPoint(80, 0))), Qt::NoButton,
                     Qt::NoButton, Qt::NoModifier);
    QApplication::sendEvent(view->plot(), &move);
    QCOMPARE(*review->cursor_time(), held);
  }

  void annotationsAreAddedAtTheCursorAndDrawn() {
    ReviewView* review = window_->review_view();
    const double t_s = *review->cursor_time();
    QSignalSpy changed(review, &ReviewView::annotations_changed);
    window_->mark_action()->trigger();  // not interactive: a default note
    QVERIFY(review->add_annotation("rattle"));
    QCOMPARE(changed.count(), 2);
    QCOMPARE(review->annotations().size(), std::size_t{2});
    QCOMPARE(review->annotations()[0].text, std::string("mark 1"));
    QCOMPARE(review->annotations()[1].t_s, t_s);
    QCOMPARE(QString::fromStdString(review->annotations()[1].recording),
             QFileInfo(kPositive).absoluteFilePath());
    QCOMPARE(window_->mark_action()->shortcut(), QKeySequence(Qt::CTRL | Qt::Key_M));
    QCOMPARE(review->annotation_list()->count(), 2);
    QVERIFY(review->annotation_list()->item(1)->text().contains("rattle"));
    // Drawn on the record view: one labelled line over every channel plot.
    QCOMPARE(window_->record_view()->marks().size(), std::size_t{2});
    int labels = 0;
    QCustomPlot* plot = window_->record_view()->plot();
    for (int i = 0; i < plot->itemCount(); ++i) {
      if (auto* text = qobject_cast<QCPItemText*>(plot->item(i));
          text && text->text() == "rattle") {
        QCOMPARE(text->position->coords().x(), t_s);
        ++labels;
      }
    }
    QCOMPARE(labels, 1);
    // Only on the recording they belong to.
    review->show_recording(window_->review_view()->recordings()[1].recording);
    QCOMPARE(window_->record_view()->marks().size(), std::size_t{0});
    review->show_recording(window_->review_view()->recordings()[0].recording);
    QCOMPARE(window_->record_view()->marks().size(), std::size_t{2});
  }

  void aSessionBringsEverythingBackInAFreshWindow() {
    ReviewView* review = window_->review_view();
    // The state to keep: the two Fig. 9 levels, a window, the cursor, the notes, the layout.
    const LevelKey negative = level_near(expected_, oscilab::analysis::Well::Negative, 1.3);
    const LevelKey positive = level_near(expected_, oscilab::analysis::Well::Positive, 1.3);
    review->select_levels({positive, negative});
    window_->record_view()->set_time_window(101.0, 104.5);
    window_->record_view()->set_cursor_time(102.0);
    auto* dock = window_->findChild<QDockWidget*>("identification_dock");
    QVERIFY(dock != nullptr);
    dock->hide();
    const nlohmann::json live = {{"host", "rig-2"}, {"port", 5025}};
    window_->live_monitor()->apply_settings(live);
    const QString path = temporary_.filePath("review.json");
    QVERIFY(window_->save_session(path));
    const auto saved = window_->current_session();

    MainWindow fresh;
    fresh.set_interactive_errors(false);
    fresh.resize(1000, 700);
    QSignalSpy analysed(&fresh, &MainWindow::analysis_finished);
    QVERIFY(fresh.open_session(path));
    QCOMPARE(fresh.opened_paths(), window_->opened_paths());
    QCOMPARE(fresh.review_view()->annotations(), review->annotations());
    QCOMPARE(fresh.review_view()->annotation_list()->count(), 2);
    QCOMPARE(fresh.live_monitor()->session_settings(), live);
    QVERIFY(fresh.findChild<QDockWidget*>("identification_dock")->isHidden());
    QVERIFY(analysed.wait(kAnalysisTimeoutMs));
    QCOMPARE(fresh.review_view()->selected_levels(), (std::vector<LevelKey>{positive, negative}));
    QCOMPARE(fresh.review_view()->loop_plot()->plottableCount(), 2);
    QVERIFY(fresh.windowTitle().startsWith("stepped_positive.flac"));
    const auto window = fresh.record_view()->time_window();
    QVERIFY(std::abs(window.start_s - 101.0) < 1e-9);
    QVERIFY(std::abs(window.end_s - 104.5) < 1e-9);
    QCOMPARE(fresh.record_view()->cursor_time(), std::optional<double>(102.0));
    QCOMPARE(fresh.analysis_settings().to_json(), window_->analysis_settings().to_json());
    // Saved again, the same session (the layout aside: the fresh window's geometry differs).
    auto again = fresh.current_session();
    again.window_geometry_base64 = saved.window_geometry_base64;
    again.window_state_base64 = saved.window_state_base64;
    QCOMPARE(oscilab::ui::session_to_json(again, "/"), oscilab::ui::session_to_json(saved, "/"));
    dock->show();
  }

  void aBadSessionFileIsReportedAndChangesNothing() {
    const QString path = temporary_.filePath("bad.json");
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(R"({"format": "oscilab-session/1", "recordings": [")" + kPositive.toUtf8() +
               R"("], "annotations": [{"recording": 0, "t_s": "soon", "text": "x"}]})");
    file.close();
    const QStringList paths = window_->opened_paths();
    const auto annotations = window_->review_view()->annotations();
    const int rows = window_->review_view()->level_table()->rowCount();
    QSignalSpy errors(window_.get(), &MainWindow::error_reported);
    QVERIFY(!window_->open_session(path));
    QCOMPARE(errors.count(), 1);
    const QString message = errors.front().front().toString();
    QCOMPARE(message, path + ": annotations[0].t_s: expected a number, got \"soon\"");
    QVERIFY(window_->statusBar()->currentMessage().contains(message));
    QCOMPARE(window_->opened_paths(), paths);
    QCOMPARE(window_->review_view()->annotations(), annotations);
    QCOMPARE(window_->review_view()->level_table()->rowCount(), rows);
    QVERIFY(!window_->analysis_running());
  }

  void missingRecordingsAreNamedAndTheOthersOpened() {
    const QString path = temporary_.filePath("partial.json");
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(R"({"format": "oscilab-session/1", "recordings": ["no_such_run.flac", ")" +
               kNegative.toUtf8() + R"("]})");
    file.close();
    MainWindow fresh;
    fresh.set_interactive_errors(false);
    QSignalSpy errors(&fresh, &MainWindow::error_reported);
    QSignalSpy analysed(&fresh, &MainWindow::analysis_finished);
    QVERIFY(fresh.open_session(path));
    QCOMPARE(errors.count(), 1);
    const QString message = errors.front().front().toString();
    QVERIFY2(message.contains("no_such_run.flac") && message.startsWith(path), qPrintable(message));
    QCOMPARE(fresh.opened_paths(), QStringList({QFileInfo(kNegative).absoluteFilePath()}));
    QVERIFY(analysed.wait(kAnalysisTimeoutMs));
    QCOMPARE(fresh.review_view()->level_table()->rowCount(),
             int(expected_.records[1].levels.size()));
  }

 private:
  QTemporaryDir temporary_;
  oscilab::analysis::CampaignAnalysis expected_;
  std::unique_ptr<MainWindow> window_;
};

QTEST_MAIN(ReviewViewTest)
#include "review_view_test.moc"

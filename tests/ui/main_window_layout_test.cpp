// GUI test of the main window on a 1366×768 laptop screen, by geometry (not pixels), under the
// offscreen platform: with both stepped-sine samples opened and analysed, the live rig running, a
// fit and a diagnosis done, the window's minimum size fits 1280×720 and the window 1366×768;
// every tab of every tab widget can be clicked (no tab behind scroll arrows or off its bar); no
// label of the live status strip or the status bar is cut or overlaps its neighbour (a label is
// as wide as its text, wraps within its height, or elides with its full text on hover); the
// tables of the diagnosis say every cell in full on hover; the residual plots are tall enough for
// their ticks; a dialog of the fit panel leaves the window's size alone; and the fit panel draws
// the measured EDC as soon as the records are analysed.
#include <QApplication>
#include <QDockWidget>
#include <QLabel>
#include <QScrollArea>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTabBar>
#include <QTabWidget>
#include <QTableWidget>
#include <QTest>

#include <qcustomplot.h>

#include "ui/identification/diagnosis_view.h"
#include "ui/identification/identification_panel.h"
#include "ui/identification/response_dialog.h"
#include "ui/live/live_monitor.h"
#include "ui/live/live_settings.h"
#include "ui/main_window.h"

using oscilab::ui::IdentificationPanel;
using oscilab::ui::LiveMonitor;
using oscilab::ui::MainWindow;

namespace {

const QString kSamples = QStringLiteral(OSCILAB_SOURCE_DIR "/samples/");
const QSize kScreen(1366, 768);          // the laptop screen
const QSize kLargestMinimum(1280, 720);  // what the window may demand at least
// The analysis of two 262 s records, a short fit and diagnosis: bounds on a hung worker.
constexpr int kAnalysisTimeoutMs = 180000;
constexpr int kJobTimeoutMs = 300000;

QString describe(const QWidget* widget) {
  return QStringLiteral("%1 \"%2\" (%3) %4x%5 at %6,%7, hint %8x%9")
      .arg(widget->metaObject()->className(), widget->objectName())
      .arg(qobject_cast<const QLabel*>(widget) ? qobject_cast<const QLabel*>(widget)->text()
                                               : QString())
      .arg(widget->width())
      .arg(widget->height())
      .arg(widget->x())
      .arg(widget->y())
      .arg(widget->sizeHint().width())
      .arg(widget->sizeHint().height());
}

// A label shows its whole text: as wide as its text, or wrapped within its height, or elided
// ("…") with the full text on hover.
bool shows_whole_text(const QLabel* label, QString& why) {
  if (label->text().isEmpty()) return true;
  if (label->wordWrap()) {
    if (label->heightForWidth(label->width()) <= label->height() + 1) return true;
    why = QStringLiteral("wrapped text %1 px high in %2 px")
              .arg(label->heightForWidth(label->width()))
              .arg(label->height());
    return false;
  }
  if (label->sizeHint().width() <= label->width()) return true;
  if (label->text().contains(QChar(0x2026)) && !label->toolTip().isEmpty()) return true;
  why =
      QStringLiteral("text %1 px wide in %2 px").arg(label->sizeHint().width()).arg(label->width());
  return false;
}

// Every visible label that is a direct child of `container` shows its whole text, stays within
// the container and overlaps none of its visible sibling labels.
void check_labels(const QWidget* container) {
  QList<const QLabel*> labels;
  for (const QLabel* label : container->findChildren<const QLabel*>(Qt::FindDirectChildrenOnly)) {
    if (label->isVisibleTo(container->window())) labels << label;
  }
  for (const QLabel* label : labels) {
    QString why;
    QVERIFY2(shows_whole_text(label, why), qPrintable(describe(label) + ": " + why));
    QVERIFY2(label->geometry().right() <= container->width(),
             qPrintable(describe(label) + " runs past " + describe(container)));
    for (const QLabel* other : labels) {
      if (other == label) continue;
      QVERIFY2(!label->geometry().intersects(other->geometry()),
               qPrintable(describe(label) + " overlaps " + describe(other)));
    }
  }
}

// Every tab of every visible tab widget of `window` can be reached by a click: its rectangle lies
// within the visible tab bar (none behind scroll arrows).
void check_tabs(const QWidget& window) {
  for (const QTabWidget* tabs : window.findChildren<const QTabWidget*>()) {
    if (!tabs->isVisible()) continue;
    const QTabBar* bar = tabs->tabBar();
    QCOMPARE(bar->count(), tabs->count());
    QVERIFY2(bar->isVisible() && bar->isEnabled(), qPrintable(describe(tabs)));
    for (int i = 0; i < bar->count(); ++i) {
      QVERIFY2(bar->isTabEnabled(i), qPrintable(tabs->tabText(i)));
      QVERIFY2(bar->rect().contains(bar->tabRect(i)),
               qPrintable(QStringLiteral("tab \"%1\" of %2 lies outside its bar (%3 px wide)")
                              .arg(tabs->tabText(i), describe(tabs))
                              .arg(bar->width())));
      // A name cut to fit says itself in full on hover.
      if (bar->tabRect(i).width() < bar->fontMetrics().horizontalAdvance(tabs->tabText(i))) {
        QVERIFY2(!tabs->tabToolTip(i).isEmpty(), qPrintable(tabs->tabText(i)));
      }
    }
  }
}

void check_window_fits(const MainWindow& window) {
  const QSize hint = window.minimumSizeHint();
  const QSize minimum = window.minimumSize();
  qInfo("minimum size hint %dx%d, window %dx%d", hint.width(), hint.height(), window.width(),
        window.height());
  QVERIFY2(
      hint.width() <= kLargestMinimum.width() && hint.height() <= kLargestMinimum.height(),
      qPrintable(QStringLiteral("minimum size hint %1x%2").arg(hint.width()).arg(hint.height())));
  QVERIFY2(
      minimum.width() <= kLargestMinimum.width() && minimum.height() <= kLargestMinimum.height(),
      qPrintable(QStringLiteral("minimum size %1x%2").arg(minimum.width()).arg(minimum.height())));
  QVERIFY2(window.width() <= kScreen.width() && window.height() <= kScreen.height(),
           qPrintable(QStringLiteral("window %1x%2").arg(window.width()).arg(window.height())));
}

}  // namespace

class MainWindowLayoutTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void initTestCase() {
    window_ = std::make_unique<MainWindow>();
    window_->set_interactive_errors(false);
    window_->resize(kScreen);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
    QSignalSpy analysed(window_.get(), &MainWindow::analysis_finished);
    QCOMPARE(window_->open_recordings(
                 {kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"}),
             2);
    QVERIFY(analysed.wait(kAnalysisTimeoutMs));
    QApplication::processEvents();
  }
  void cleanupTestCase() {
    window_->live_monitor()->stop();
    window_.reset();
  }

  void reviewFitsTheScreenWithThePanelShown() {
    auto* dock = window_->findChild<QDockWidget*>("identification_dock");
    QVERIFY(dock != nullptr && dock->isVisible());
    check_window_fits(*window_);
    check_tabs(*window_);
    check_labels(window_->statusBar());
  }

  // The fit panel draws what it would fit at once: both wells' measured EDC, no model yet, and
  // a hint that counts the levels instead of asking for recordings already there.
  void theMeasuredEdcIsDrawnBeforeAnyFit() {
    IdentificationPanel* panel = window_->identification_panel();
    QCustomPlot* edc = nullptr;
    for (int i = 0; i < panel->tabs()->count(); ++i) {
      if (panel->tabs()->tabText(i) == "EDC")
        edc = qobject_cast<QCustomPlot*>(panel->tabs()->widget(i));
    }
    QVERIFY(edc != nullptr);
    int points = 0;
    for (int g = 0; g < edc->graphCount(); ++g) points += edc->graph(g)->dataCount();
    QCOMPARE(edc->graphCount(), 2);  // one per well, measured ±3σ
    QCOMPARE(points, 52);            // 26 levels per sample
    QVERIFY(edc->legend->visible());
    QVERIFY2(panel->status_label()->text().startsWith("Measured: 26 levels"),
             qPrintable(panel->status_label()->text()));
  }

  void liveTabFitsTheScreenWithTheRigRunning() {
    LiveMonitor* live = window_->live_monitor();
    window_->central_tabs()->setCurrentWidget(live);
    oscilab::ui::LiveSettings settings = live->settings();
    settings.source = oscilab::ui::LiveSourceKind::Rig;
    settings.speed = 10.0;
    settings.rig_f0_n = 0.8;
    live->set_settings(settings);
    QVERIFY2(live->start(), qPrintable(live->message()));
    QTest::qWait(1500);  // figures in every label
    check_window_fits(*window_);
    check_tabs(*window_);
    auto* strip = live->findChild<QWidget*>("status_strip");
    QVERIFY(strip != nullptr && strip->isVisible());
    QVERIFY(strip->findChildren<QLabel*>().size() >= 17);
    check_labels(strip);
    check_labels(strip->parentWidget());  // the strip beside the level's warning
    check_labels(live);                   // the source's message
    live->stop();
    window_->central_tabs()->setCurrentIndex(0);
    QApplication::processEvents();
  }

  void fitAndDiagnosisFitTheScreenAndReadInFull() {
    IdentificationPanel* panel = window_->identification_panel();
    panel->set_fit_settings("ga", 2000, 6, 1);
    panel->set_diagnosis_budget(300, 200);
    QSignalSpy done(panel, &IdentificationPanel::job_finished);
    panel->start_fit();
    QVERIFY(done.wait(kJobTimeoutMs));
    QVERIFY2(done.takeFirst().at(0).toString().startsWith("Fit: "),
             qPrintable(panel->status_label()->text()));
    panel->start_diagnosis();
    QVERIFY(done.wait(kJobTimeoutMs));
    QVERIFY2(done.takeFirst().at(0).toString().startsWith("Diagnosis: "),
             qPrintable(panel->status_label()->text()));
    QApplication::processEvents();
    check_window_fits(*window_);
    // Every page of the panel, one after the other.
    QTabWidget* tabs = panel->tabs();
    for (int i = 0; i < tabs->count(); ++i) {
      tabs->setCurrentIndex(i);
      QApplication::processEvents();
      check_tabs(*window_);
    }
    // The candidates' outcome and evidence, the σ budget's σ total: in view, or in full on hover.
    QCOMPARE(panel->budget_table()->rowCount(), 52);  // every level of both wells
    for (QTableWidget* table : {panel->step_table(), panel->budget_table()}) {
      for (int r = 0; r < table->rowCount(); ++r) {
        for (int c = 0; c < table->columnCount(); ++c) {
          const QTableWidgetItem* item = table->item(r, c);
          QVERIFY(item != nullptr);
          QVERIFY2(item->toolTip().contains(item->text()),
                   qPrintable(QStringLiteral("row %1 column %2: \"%3\" without its tooltip")
                                  .arg(r)
                                  .arg(c)
                                  .arg(item->text())));
        }
      }
    }
    // A dialog of the fit panel comes and goes: the window keeps its size.
    oscilab::ui::ResponseDialog* dialog = panel->open_branch_dialog();
    QVERIFY(dialog != nullptr);
    QVERIFY(QTest::qWaitForWindowExposed(dialog));
    dialog->close();
    QApplication::processEvents();
    check_window_fits(*window_);
    QCOMPARE(window_->size(), kScreen);
    // The residuals: two panels (one per well) with room for their ticks and legend.
    QCustomPlot* residuals = panel->residual_plot();
    tabs->setCurrentIndex(tabs->indexOf(panel->findChild<QWidget*>("residual_page")));
    QApplication::processEvents();
    QVERIFY2(residuals->height() >= 2 * 150, qPrintable(describe(residuals)));
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

QTEST_MAIN(MainWindowLayoutTest)
#include "main_window_layout_test.moc"

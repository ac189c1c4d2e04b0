// GUI test of how the main window takes input besides its menus' dialogs, under the offscreen
// platform on the bundled samples: files dropped on the window open as File ▸ Open and File ▸
// Open session would (a recording dropped with its sidecar opens once); a live recording opens
// for review and joins the fit set only when the offer is clicked; the keyboard zooms the plot
// under the mouse in and out, undoes the last zoom and resets it; Alt+Down and Alt+Up step
// through the level table; Help ▸ Keyboard shortcuts lists the keys; the review's plots read out
// the value under the mouse; every text in the window spells its symbols and units one way; the
// plots follow a dark palette, their data lines kept legible on it.
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <QAbstractButton>
#include <QApplication>
#include <QComboBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMimeData>
#include <QMouseEvent>
#include <QPushButton>
#include <QRegularExpression>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QToolTip>

#include <qcustomplot.h>

#include "ui/export_menu.h"
#include "ui/identification/identification_panel.h"
#include "ui/live/live_monitor.h"
#include "ui/main_window.h"
#include "ui/review/level_table.h"
#include "ui/review/record_view.h"
#include "ui/review/review_view.h"

using oscilab::ui::MainWindow;

namespace {

const QString kSamples = QStringLiteral(OSCILAB_SOURCE_DIR "/samples/");
constexpr int kAnalysisTimeoutMs = 60000;  // one 262 s record: a bound on a hung worker

// Drags `files` over `window` and drops them there, as a file manager would; true when the
// window accepted the drag.
bool drop_files(MainWindow& window, const QStringList& files) {
  QMimeData data;
  QList<QUrl> urls;
  for (const QString& file : files) urls << QUrl::fromLocalFile(file);
  urls << QUrl("https://example.org/run1.flac");  // not a local file: left out
  data.setUrls(urls);
  const QPoint at = window.rect().center();
  QDragEnterEvent enter(at, Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&window, &enter);
  if (!enter.isAccepted()) return false;
  QDropEvent drop(at, Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&window, &drop);
  return drop.isAccepted();
}

double time_span(const MainWindow& window) {
  return window.record_view()->plot()->axisRect(0)->axis(QCPAxis::atBottom)->range().size();
}

std::unique_ptr<MainWindow> shown_window() {
  auto window = std::make_unique<MainWindow>();
  window->set_interactive_errors(false);
  window->show();
  window->activateWindow();
  return window;
}

// The tooltip a mouse resting at the middle of `plot`'s (first) axis rect shows, with the tab
// holding the plot brought to the front so that it is laid out.
QString hover_tooltip(QTabWidget& tabs, QWidget* page, QCustomPlot* plot) {
  tabs.setCurrentWidget(page);
  QApplication::processEvents();
  plot->replot();
  QEvent enter(QEvent::Enter);
  QApplication::sendEvent(plot, &enter);
  const QPointF at = plot->axisRect()->rect().center();
  QMouseEvent move(QEvent::MouseMove, at, plot->mapToGlobal(at), Qt::NoButton, Qt::NoButton,
                   Qt::NoModifier);
  QApplication::sendEvent(plot, &move);
  return QToolTip::text();
}

// Every text the window's widgets show or say on hover: labels, buttons, group boxes, tabs, table
// headers, combo box items, actions, and the plots' axis labels, titles and legend names.
QStringList shown_texts(const QWidget& root) {
  QStringList texts;
  for (const QWidget* w : root.findChildren<const QWidget*>()) {
    texts << w->toolTip() << w->windowTitle();
    if (auto* label = qobject_cast<const QLabel*>(w)) texts << label->text();
    if (auto* button = qobject_cast<const QAbstractButton*>(w)) texts << button->text();
    if (auto* group = qobject_cast<const QGroupBox*>(w)) texts << group->title();
    if (auto* tabs = qobject_cast<const QTabWidget*>(w)) {
      for (int i = 0; i < tabs->count(); ++i) texts << tabs->tabText(i) << tabs->tabToolTip(i);
    }
    if (auto* table = qobject_cast<const QTableWidget*>(w)) {
      for (int c = 0; c < table->columnCount(); ++c) {
        if (const QTableWidgetItem* item = table->horizontalHeaderItem(c)) texts << item->text();
      }
    }
    if (auto* box = qobject_cast<const QComboBox*>(w)) {
      for (int i = 0; i < box->count(); ++i) texts << box->itemText(i);
    }
    if (auto* plot = qobject_cast<QCustomPlot*>(const_cast<QWidget*>(w))) {
      for (QCPAxisRect* rect : plot->axisRects()) {
        for (QCPAxis* axis : rect->axes()) texts << axis->label();
      }
      for (int i = 0; i < plot->plottableCount(); ++i) texts << plot->plottable(i)->name();
      for (int i = 0; i < plot->plotLayout()->elementCount(); ++i) {
        if (auto* title = qobject_cast<QCPTextElement*>(plot->plotLayout()->elementAt(i))) {
          texts << title->text();
        }
      }
    }
  }
  for (const QAction* action : root.findChildren<const QAction*>()) {
    texts << action->text() << action->toolTip();
  }
  return texts;
}

}  // namespace

class MainWindowInputTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void droppedRecordingOpensOnceWithItsSidecar() {
    MainWindow window;
    window.set_interactive_errors(false);
    QSignalSpy opened(&window, &MainWindow::recording_opened);
    QVERIFY(drop_files(window,
                       {kSamples + "stepped_positive.flac", kSamples + "stepped_positive.json"}));
    QTRY_COMPARE(opened.count(), 1);
    QCOMPARE(window.opened_paths(), QStringList{kSamples + "stepped_positive.flac"});
    // Its sidecar alone opens the data file beside it.
    QVERIFY(drop_files(window, {kSamples + "stepped_negative.json"}));
    QTRY_COMPARE(opened.count(), 2);
    QCOMPARE(window.opened_paths().at(1), kSamples + "stepped_negative.flac");
    // Nothing to open: the drag is refused.
    QVERIFY(!drop_files(window, {}));
  }

  void droppedSessionReplacesTheReview() {
    QTemporaryDir dir;
    const QString session = dir.filePath("review.json");
    {
      MainWindow saved;
      saved.set_interactive_errors(false);
      QVERIFY(saved.open_recording(kSamples + "stepped_negative.flac"));
      QVERIFY(saved.save_session(session));
    }
    MainWindow window;
    window.set_interactive_errors(false);
    QVERIFY(window.open_recording(kSamples + "random.flac"));
    QVERIFY(drop_files(window, {session}));
    QTRY_COMPARE(window.opened_paths(), QStringList{kSamples + "stepped_negative.flac"});
  }

  void liveRecordingJoinsTheFitSetOnlyWhenAdded() {
    MainWindow window;
    window.set_interactive_errors(false);
    QSignalSpy opened(&window, &MainWindow::recording_opened);
    const QString path = kSamples + "stepped_positive.flac";
    Q_EMIT window.live_monitor()->recording_finished(path);
    QCOMPARE(opened.count(), 1);
    QCOMPARE(window.opened_paths(), QStringList{path});
    QVERIFY(window.identification_panel()->recordings().empty());  // opened for review only
    QPushButton* offer = window.fit_set_offer_button();
    QVERIFY(offer->isVisibleTo(&window));
    QVERIFY2(offer->text().contains("stepped_positive.flac"), qPrintable(offer->text()));
    QTest::mouseClick(offer, Qt::LeftButton);
    QCOMPARE(window.identification_panel()->recordings(),
             std::vector<std::string>{path.toStdString()});
    QVERIFY(!offer->isVisibleTo(&window));
    // A recording opened with File ▸ Open still joins at once.
    QVERIFY(window.open_recording(kSamples + "stepped_negative.flac"));
    QCOMPARE(window.identification_panel()->recordings().size(), std::size_t{2});
    // Two recordings made before the offer is taken: one click adds both.
    MainWindow second;
    second.set_interactive_errors(false);
    Q_EMIT second.live_monitor()->recording_finished(path);
    Q_EMIT second.live_monitor()->recording_finished(kSamples + "stepped_negative.flac");
    QCOMPARE(second.fit_set_offer_button()->text(), QString("Add 2 recordings to the fit set"));
    QTest::mouseClick(second.fit_set_offer_button(), Qt::LeftButton);
    QCOMPARE(second.identification_panel()->recordings().size(), std::size_t{2});
  }

  void zoomKeysZoomUndoAndReset() {
    auto window = shown_window();
    QVERIFY(QTest::qWaitForWindowActive(window.get()));
    QVERIFY(window->open_recording(kSamples + "stepped_positive.flac"));
    const double whole = time_span(*window);
    QEvent enter(QEvent::Enter);  // the plot under the mouse is the one zoomed
    QApplication::sendEvent(window->record_view()->plot(), &enter);
    QCOMPARE(window->export_menu()->plot_to_export(), window->record_view()->plot());
    QVERIFY(whole > 200.0);  // s: the 262 s record
    QTest::keyClick(window.get(), Qt::Key_Plus, Qt::ControlModifier);
    QCOMPARE(time_span(*window), whole / 1.25);
    QTest::keyClick(window.get(), Qt::Key_Plus, Qt::ControlModifier);
    QCOMPARE(time_span(*window), whole / 1.25 / 1.25);
    QTest::keyClick(window.get(), Qt::Key_Backspace);  // undo the last zoom
    QCOMPARE(time_span(*window), whole / 1.25);
    QTest::keyClick(window.get(), Qt::Key_Minus, Qt::ControlModifier);
    QCOMPARE(time_span(*window), whole);
    QTest::keyClick(window.get(), Qt::Key_Plus, Qt::ControlModifier);
    QTest::keyClick(window.get(), Qt::Key_0, Qt::ControlModifier);  // the whole record
    QCOMPARE(time_span(*window), whole);
    // Another plot under the mouse zooms in both directions; Ctrl+Z undoes it.
    QCustomPlot* edc = window->identification_panel()->edc_plot();
    QVERIFY(edc->isVisible());
    QApplication::sendEvent(edc, &enter);
    const QCPRange x = edc->xAxis->range();
    const QCPRange y = edc->yAxis->range();
    QTest::keyClick(window.get(), Qt::Key_Plus, Qt::ControlModifier);
    QCOMPARE(edc->xAxis->range().size(), x.size() / 1.25);
    QCOMPARE(edc->yAxis->range().size(), y.size() / 1.25);
    QCOMPARE(time_span(*window), whole);  // the record view is left alone
    QTest::keyClick(window.get(), Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(edc->xAxis->range(), x);
    QCOMPARE(edc->yAxis->range(), y);
    // In a text field Backspace and Ctrl+Z edit the text, not the zoom.
    auto* edit = new QLineEdit(window.get());
    edit->show();
    edit->setFocus();
    QTRY_VERIFY(edit->hasFocus());
    QTest::keyClicks(edit, "ab");
    QTest::keyClick(edit, Qt::Key_Backspace);
    QCOMPARE(edit->text(), QString("a"));
    QCOMPARE(time_span(*window), whole);
  }

  void altArrowsStepThroughTheLevels() {
    auto window = shown_window();
    QVERIFY(QTest::qWaitForWindowActive(window.get()));
    QSignalSpy analysed(window.get(), &MainWindow::analysis_finished);
    QVERIFY(window->open_recording(kSamples + "stepped_positive.flac"));
    QVERIFY(analysed.wait(kAnalysisTimeoutMs));
    const oscilab::ui::LevelTable* table = window->review_view()->level_table();
    QVERIFY(table->rowCount() > 2);
    const auto selected = [&] { return window->review_view()->selected_levels(); };
    QTest::keyClick(window.get(), Qt::Key_Down, Qt::AltModifier);
    QCOMPARE(selected(), std::vector{table->key_at(0)});
    QTest::keyClick(window.get(), Qt::Key_Down, Qt::AltModifier);
    QCOMPARE(selected(), std::vector{table->key_at(1)});
    QTest::keyClick(window.get(), Qt::Key_Up, Qt::AltModifier);
    QCOMPARE(selected(), std::vector{table->key_at(0)});
    QTest::keyClick(window.get(), Qt::Key_Up, Qt::AltModifier);  // stays on the first
    QCOMPARE(selected(), std::vector{table->key_at(0)});
  }

  // The Cycles and restoring-force plots read out the value under the mouse with its unit.
  void plotsReadOutTheValueUnderTheMouse() {
    auto window = shown_window();
    QVERIFY(QTest::qWaitForWindowActive(window.get()));
    QSignalSpy analysed(window.get(), &MainWindow::analysis_finished);
    QVERIFY(window->open_recording(kSamples + "stepped_positive.flac"));
    QVERIFY(analysed.wait(kAnalysisTimeoutMs));
    oscilab::ui::ReviewView* review = window->review_view();
    auto* tabs = review->findChild<QTabWidget*>("review_tabs");
    QVERIFY(tabs != nullptr);
    const QRegularExpression cycles(
        QStringLiteral("^time = [-0-9.e]+ s   EDC per cycle = [-0-9.e]+ mJ$"));
    const QString cycle_tip = hover_tooltip(*tabs, review->cycle_plot(), review->cycle_plot());
    QVERIFY2(cycles.match(cycle_tip).hasMatch(), qPrintable(cycle_tip));
    QWidget* slices = tabs->widget(2);
    const QString slice_tip = hover_tooltip(*tabs, slices, review->stiffness_plot());
    QVERIFY2(slice_tip.startsWith("z = ") && slice_tip.contains(" mm   ") &&
                 slice_tip.contains("R = ") && slice_tip.contains(" N"),
             qPrintable(slice_tip));
    // The record view keeps its own readout line: no tooltip of this kind there.
    QToolTip::hideText();
    QTRY_VERIFY(!QToolTip::isVisible());
    QCustomPlot* record = window->record_view()->plot();
    const QPointF middle = record->rect().center();
    QMouseEvent move(QEvent::MouseMove, middle, record->mapToGlobal(middle), Qt::NoButton,
                     Qt::NoButton, Qt::NoModifier);
    QApplication::sendEvent(record, &move);
    QVERIFY(!QToolTip::isVisible() || !QToolTip::text().contains(" = "));
  }

  // One spelling of each symbol and unit in the whole window, the Unicode one: z₊*, z₋*, σ, m/s².
  void unitTextIsSpelledOneWay() {
    MainWindow window;
    window.set_interactive_errors(false);
    QSignalSpy analysed(&window, &MainWindow::analysis_finished);
    QVERIFY(window.open_recordings(
                {kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"}) == 2);
    QVERIFY(analysed.wait(kAnalysisTimeoutMs));
    for (const QString& text : shown_texts(window)) {
      for (const char* ascii : {"z+*", "z-*", "sigma", "^2", "m/s2"}) {
        QVERIFY2(!text.contains(QLatin1String(ascii)), qPrintable(ascii + (": " + text)));
      }
    }
  }

  // The plots follow the palette: a dark one (View ▸ Theme ▸ Dark, or the system's) draws them
  // dark (background, axes, tick labels), a colour a plot chose itself stays, and System brings
  // back the light default.
  void plotsFollowADarkPalette() {
    auto window = shown_window();
    QVERIFY(QTest::qWaitForWindowExposed(window.get()));
    QVERIFY(window->open_recording(kSamples + "stepped_positive.flac"));
    QCustomPlot* cycles = window->review_view()->cycle_plot();
    QCustomPlot* record = window->record_view()->plot();
    const auto background = [](QCustomPlot* plot) {
      return plot->toPixmap(200, 150).toImage().pixelColor(1, 1);  // outside the axes
    };
    QCOMPARE(background(record), QColor(Qt::white));
    const QColor channel_title =
        qobject_cast<QCPTextElement*>(record->plotLayout()->elementAt(0))->textColor();
    // Every data line's own colour, to check on the dark palette and after it: the loops of the
    // first look among them, a well's later loops in darker shades of its colour.
    QCustomPlot* loops = window->review_view()->loop_plot();
    QTRY_VERIFY(loops->plottableCount() >= 2);
    std::vector<std::pair<QCPAbstractPlottable*, QColor>> own_pens;
    for (QCustomPlot* plot : {cycles, record, loops}) {
      for (int i = 0; i < plot->plottableCount(); ++i) {
        own_pens.emplace_back(plot->plottable(i), plot->plottable(i)->pen().color());
      }
    }
    QVERIFY(!own_pens.empty());
    QMenu* themes = window->findChild<QMenu*>("theme_menu");
    QVERIFY(themes != nullptr && themes->actions().size() == 3);
    themes->actions().at(2)->trigger();  // Dark
    QApplication::processEvents();
    const QPalette dark = QApplication::palette();
    QVERIFY(dark.color(QPalette::Base).lightness() < 80);
    for (QCustomPlot* plot : {cycles, record}) {
      QCOMPARE(background(plot), dark.color(QPalette::Base));
      QCOMPARE(plot->xAxis->tickLabelColor(), dark.color(QPalette::Text));
      QCOMPARE(plot->xAxis->basePen().color(), dark.color(QPalette::Text));
    }
    QCOMPARE(qobject_cast<QCPTextElement*>(record->plotLayout()->elementAt(0))->textColor(),
             channel_title);  // the channel's own colour
    // Every data line shows on the dark background: WCAG 2's contrast ratio (its relative
    // luminance of sRGB, computed here on its own) at least 3:1, its least for graphics. The
    // wells' Okabe–Ito blue darkened for a second loop is below it, so some line had to change.
    const auto luminance = [](const QColor& c) {
      const auto linear = [](double v) {
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
      };
      return 0.2126 * linear(c.redF()) + 0.7152 * linear(c.greenF()) + 0.0722 * linear(c.blueF());
    };
    const double base_luminance = luminance(dark.color(QPalette::Base));
    int changed = 0;
    for (const auto& [plottable, own] : own_pens) {
      plottable->parentPlot()->replot();
      const QColor shown = plottable->pen().color();
      QVERIFY2((luminance(shown) + 0.05) / (base_luminance + 0.05) >= 3.0,
               qPrintable(shown.name() + " on " + dark.color(QPalette::Base).name()));
      changed += shown != own;
    }
    QVERIFY(changed > 0);
    // The wells' names in the loop plot, in their wells' colours, read on the dark background:
    // WCAG's 4.5:1 for text.
    int well_labels = 0;
    for (int i = 0; i < loops->itemCount(); ++i) {
      if (auto* label = qobject_cast<QCPItemText*>(loops->item(i));
          label && label->text().startsWith("around")) {
        QVERIFY2((luminance(label->color()) + 0.05) / (base_luminance + 0.05) >= 4.5,
                 qPrintable(label->text() + ": " + label->color().name()));
        ++well_labels;
      }
    }
    QVERIFY(well_labels > 0);
    // Back on the light palette each line has its own colour again.
    themes->actions().at(0)->trigger();
    QApplication::processEvents();
    for (const auto& [plottable, own] : own_pens) {
      plottable->parentPlot()->replot();
      QCOMPARE(plottable->pen().color(), own);
    }
    themes->actions().at(2)->trigger();
    QApplication::processEvents();
    // The cursor lines (no marks yet) are drawn in the text colour, not a grey lost on the dark.
    for (QCustomPlot* plot : {cycles, record}) {
      int lines = 0;
      for (int i = 0; i < plot->itemCount(); ++i) {
        if (auto* line = qobject_cast<QCPItemStraightLine*>(plot->item(i))) {
          QCOMPARE(line->pen().color(), dark.color(QPalette::Text));
          ++lines;
        }
      }
      QVERIFY(lines > 0);
    }
    // A plot rebuilt under the dark palette (another recording shown: new axis rects) is dark.
    QVERIFY(window->open_recording(kSamples + "stepped_negative.flac"));
    record->replot();
    QCOMPARE(record->axisRect(0)->axis(QCPAxis::atBottom)->tickLabelColor(),
             dark.color(QPalette::Text));
    themes->actions().at(0)->trigger();  // System: the palette the application started with
    QApplication::processEvents();
    QCOMPARE(background(record), QColor(Qt::white));
    QCOMPARE(record->xAxis->tickLabelColor(), QColor(Qt::black));
    // A plot of its own, given a dark palette directly, follows it too.
    // Its markers without a pen of their own (open circles drawn with the graph's pen) keep
    // drawing with the graph's pen, which is made legible: given a pen, they would vanish.
    QCustomPlot alone;
    QCPGraph* points = alone.addGraph();
    points->setPen(QPen(QColor(0, 84, 132)));
    points->setLineStyle(QCPGraph::lsNone);
    points->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, 6));
    alone.show();
    alone.setPalette(dark);
    QApplication::processEvents();
    alone.replot();
    QCOMPARE(background(&alone), dark.color(QPalette::Base));
    QVERIFY(!points->scatterStyle().isPenDefined());
    QVERIFY((luminance(points->pen().color()) + 0.05) / (base_luminance + 0.05) >= 3.0);
  }

  void helpListsTheShortcuts() {
    MainWindow window;
    const QStringList lines = window.shortcut_lines();
    for (const QString& expected : {QStringLiteral("View \u25b8 Zoom in: Ctrl++"),
                                    QStringLiteral("View \u25b8 Zoom out: Ctrl+-"),
                                    QStringLiteral("View \u25b8 Reset zoom: Ctrl+0"),
                                    QStringLiteral("View \u25b8 Undo zoom: Ctrl+Z, Backspace"),
                                    QStringLiteral("Review \u25b8 Next level: Alt+Down"),
                                    QStringLiteral("Review \u25b8 Previous level: Alt+Up"),
                                    QStringLiteral("File \u25b8 Open: Ctrl+O")}) {
      bool found = false;
      for (const QString& line : lines) found = found || line.startsWith(expected);
      QVERIFY2(found, qPrintable(expected + " not in:\n" + lines.join('\n')));
    }
  }
};

QTEST_MAIN(MainWindowInputTest)
#include "main_window_input_test.moc"

// oscilab: the desktop app. `oscilab [REC...]` opens a window on recordings (the first is shown,
// all are analysed for the review and join the fit and diagnosis panel); `oscilab --session FILE`
// opens a saved session; `oscilab --screenshot OUT.png [--cursor T] [--window T0:T1]
// [--level R:L,...] [--tab levels|cycles|rfs|annotations] [--mark T:NOTE] [--hide-panel]
// [--run fit|diagnose] [--dialog hbm|map|figures] REC...` saves a picture of that window (after
// the analysis, and the fit or diagnosis if asked; with --dialog, of that dialog of the fit
// panel once computed) and exits. `--live rig|REC` shows the Live tab running that source.
#include <cstdio>
#include <memory>
#include <vector>

#include <QApplication>
#include <QCommandLineParser>
#include <QDockWidget>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>

#include <qcustomplot.h>

#include "ui/figure_dialog.h"
#include "ui/identification_panel.h"
#include "ui/live_monitor.h"
#include "ui/main_window.h"
#include "ui/record_view.h"
#include "ui/response_dialog.h"
#include "ui/review_view.h"

namespace {

// Time the event loop gets to lay out and paint the window before a screenshot, in ms.
constexpr int kScreenshotSettleMs = 500;

// "0:11,1:11" → levels (record index : level index); malformed parts are skipped.
std::vector<oscilab::ui::LevelKey> parse_levels(const QString& text) {
  std::vector<oscilab::ui::LevelKey> keys;
  for (const QString& part : text.split(',', Qt::SkipEmptyParts)) {
    const QStringList numbers = part.split(':');
    bool ok_record = false, ok_level = false;
    if (numbers.size() != 2) continue;
    const int record = numbers[0].toInt(&ok_record);
    const int level = numbers[1].toInt(&ok_level);
    if (ok_record && ok_level) keys.push_back({record, level});
  }
  return keys;
}

}  // namespace

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QApplication::setApplicationName("Oscilab");
  QApplication::setOrganizationName("Oscilab");

  QCommandLineParser parser;
  parser.setApplicationDescription("Oscilab: tests of nonlinear oscillators on a shaking table.");
  parser.addHelpOption();
  parser.addPositionalArgument(
      "recordings", "Recordings to open (each with its JSON sidecar); the first is shown.",
      "[REC...]");
  const QCommandLineOption screenshot_option(
      "screenshot", "Save a PNG of the window to <png> and exit (no dialogs).", "png");
  const QCommandLineOption size_option("size", "Window size for --screenshot (default 1280x800).",
                                       "WxH", "1280x800");
  const QCommandLineOption session_option("session", "Open the session <file>.", "file");
  const QCommandLineOption cursor_option("cursor", "Place the readout cursor at <t> seconds.", "t");
  const QCommandLineOption window_option("window", "Show the time window <t0:t1> in seconds.",
                                         "t0:t1");
  const QCommandLineOption level_option(
      "level", "Select levels once analysed: record:level indices, comma-separated (0:11,1:11).",
      "levels");
  const QCommandLineOption tab_option(
      "tab", "Review tab to show: levels | cycles | rfs | annotations.", "tab");
  const QCommandLineOption mark_option(
      "mark", "Annotate the recording shown at <t> seconds with a note (t:note; repeatable).",
      "t:note");
  const QCommandLineOption hide_panel_option("hide-panel", "Hide the fit and diagnosis panel.");
  const QCommandLineOption run_option(
      "run", "Run a fit or a diagnosis of the recordings in the panel first: fit | diagnose.",
      "job");
  const QCommandLineOption dialog_option(
      "dialog",
      "With --run fit and --screenshot: open a dialog of the fit panel once the fit ended and "
      "save its picture instead: hbm (the HBM branches) | map (the bifurcation map) | figures.",
      "dialog");
  const QCommandLineOption live_option(
      "live",
      "Show the Live tab running <source>: rig (the virtual rig stepping 0.2 to 2.7 N at 20x) "
      "or a recording to replay at 10x; with --screenshot, the picture is taken after 7 s.",
      "source");
  parser.addOptions({screenshot_option, size_option, session_option, cursor_option, window_option,
                     level_option, tab_option, mark_option, hide_panel_option, run_option,
                     dialog_option, live_option});
  parser.process(app);

  const QString screenshot_path = parser.value(screenshot_option);
  const bool screenshot = !screenshot_path.isEmpty();
  oscilab::ui::MainWindow window;
  window.set_interactive_errors(!screenshot);
  oscilab::ui::ReviewView* review = window.review_view();

  const QStringList size = parser.value(size_option).split('x');
  if (screenshot && size.size() == 2) window.resize(size[0].toInt(), size[1].toInt());
  if (parser.isSet(hide_panel_option)) {
    if (auto* dock = window.findChild<QDockWidget*>("identification_dock")) dock->hide();
  }
  window.show();

  bool opened = true;
  if (parser.isSet(session_option)) opened = window.open_session(parser.value(session_option));
  const QStringList recordings = parser.positionalArguments();
  if (!recordings.isEmpty()) {
    opened = window.open_recordings(recordings) == recordings.size() && opened;
  }
  const QString tab = parser.value(tab_option);
  const QStringList tabs = {"levels", "cycles", "rfs", "annotations"};
  if (tabs.contains(tab)) review->tabs()->setCurrentIndex(int(tabs.indexOf(tab)));

  // What the options ask of the review once the analysis is shown: levels, then the time window
  // and the cursor (which a level selection would otherwise move), then the notes.
  const auto apply_view = [&] {
    const auto levels = parse_levels(parser.value(level_option));
    if (!levels.empty()) review->select_levels(levels);
    const QStringList window_s = parser.value(window_option).split(':');
    if (window_s.size() == 2) {
      window.record_view()->set_time_window(window_s[0].toDouble(), window_s[1].toDouble());
    }
    if (parser.isSet(cursor_option)) {
      window.record_view()->set_cursor_time(parser.value(cursor_option).toDouble());
    }
    for (const QString& mark : parser.values(mark_option)) {
      const qsizetype colon = mark.indexOf(':');
      if (colon <= 0) continue;
      review->set_cursor_time(mark.left(colon).toDouble());
      review->add_annotation(mark.mid(colon + 1));
    }
    if (parser.isSet(cursor_option)) {  // the notes moved the cursor
      window.record_view()->set_cursor_time(parser.value(cursor_option).toDouble());
    }
  };
  const bool analysing = window.analysis_running();
  if (!analysing) apply_view();

  if (!screenshot) {
    if (analysing) {
      auto once = std::make_shared<QMetaObject::Connection>();
      *once = QObject::connect(&window, &oscilab::ui::MainWindow::analysis_finished, &window,
                               [once, apply_view] {
                                 QObject::disconnect(*once);
                                 apply_view();
                               });
    }
    return QApplication::exec();
  }

  if (!opened) {
    std::fprintf(stderr, "oscilab: %s\n", qPrintable(window.statusBar()->currentMessage()));
    return 1;
  }
  int status = 0;
  const auto grab = [&] {
    QTimer::singleShot(kScreenshotSettleMs, &window, [&] {
      window.record_view()->plot()->replot();
      if (!window.grab().save(screenshot_path)) {
        std::fprintf(stderr, "oscilab: cannot write %s\n", qPrintable(screenshot_path));
        status = 1;
      }
      QApplication::quit();
    });
  };
  // The picture waits for the analysis and for the job asked for, whichever ends last.
  const QString job = parser.value(run_option);
  const bool run_job = job == "fit" || job == "diagnose";
  int waiting = (analysing ? 1 : 0) + (run_job ? 1 : 0);
  const auto done = [&] {
    if (--waiting == 0) grab();
  };
  bool analysed = false;
  if (analysing) {
    QObject::connect(&window, &oscilab::ui::MainWindow::analysis_finished, &window, [&] {
      if (analysed) return;  // the picture shows the first analysis
      analysed = true;
      apply_view();
      done();
    });
  }
  // --dialog: once the fit ended, the dialog is opened and computed, and its picture taken.
  const QString dialog = parser.value(dialog_option);
  const auto grab_dialog = [&](QWidget* shown) {
    if (shown != nullptr && parser.isSet(size_option) && size.size() == 2) {
      shown->resize(size[0].toInt(), size[1].toInt());  // --size is the dialog's
    }
    QTimer::singleShot(kScreenshotSettleMs, &window, [&, shown] {
      if (shown == nullptr || !shown->grab().save(screenshot_path)) {
        std::fprintf(stderr, "oscilab: cannot write %s\n", qPrintable(screenshot_path));
        status = 1;
      }
      QApplication::quit();
    });
  };
  const auto open_dialog = [&] {
    auto* panel = window.identification_panel();
    if (dialog == "figures") {
      QObject::connect(panel, &oscilab::ui::IdentificationPanel::figures_shown, &window,
                       [&, panel] { grab_dialog(panel->figures_dialog()); });
      panel->show_figures();
      return;
    }
    oscilab::ui::ResponseDialog* shown =
        dialog == "map" ? panel->open_map_dialog() : panel->open_branch_dialog();
    if (shown == nullptr) {
      grab_dialog(nullptr);
      return;
    }
    QObject::connect(shown, &oscilab::ui::ResponseDialog::computed, &window,
                     [&, shown] { grab_dialog(shown); });
  };
  if (run_job) {
    auto* panel = window.identification_panel();
    QObject::connect(panel, &oscilab::ui::IdentificationPanel::job_finished, &window, [&] {
      if (dialog.isEmpty() || job != "fit") {
        done();
      } else {
        open_dialog();
      }
    });
    if (job == "fit") {
      panel->start_fit();
    } else {
      panel->start_diagnosis();
    }
  }
  // --live: the Live tab with a source running; the picture after 7 s of it.
  if (parser.isSet(live_option)) {
    auto* live = window.findChild<oscilab::ui::LiveMonitor*>("live_monitor");
    window.central_tabs()->setCurrentWidget(live);
    oscilab::ui::LiveSettings settings = live->settings();
    const QString source = parser.value(live_option);
    settings.source =
        source == "rig" ? oscilab::ui::LiveSourceKind::Rig : oscilab::ui::LiveSourceKind::Replay;
    settings.replay_path = source.toStdString();
    settings.speed = source == "rig" ? 20.0 : 10.0;
    live->set_settings(settings);
    // §3.2's levels, 6 s each: 7 s at 20x reach the 23rd.
    if (source == "rig") {
      live->set_rig_schedule(oscilab::ui::stepped_schedule(0.2, 2.7, 0.1, 6, 1, 9));
    }
    if (!live->start()) {
      std::fprintf(stderr, "oscilab: %s\n", qPrintable(live->message()));
      return 1;
    }
    if (screenshot) {
      ++waiting;
      QTimer::singleShot(7000, &window, done);
    }
  }
  if (waiting == 0) grab();
  QApplication::exec();
  return status;
}

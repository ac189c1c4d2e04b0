// oscilab: the desktop app. `oscilab [REC...]` opens a window on recordings (the first is shown,
// all join the fit and diagnosis panel); `oscilab --screenshot OUT.png [--cursor T]
// [--run fit|diagnose] REC...` saves a picture of that window (after the fit or diagnosis, if
// asked) and exits.
#include <cstdio>

#include <QApplication>
#include <QCommandLineParser>
#include <QStatusBar>
#include <QTimer>

#include <qcustomplot.h>

#include "ui/identification_panel.h"
#include "ui/main_window.h"
#include "ui/record_view.h"

namespace {

// Time the event loop gets to lay out and paint the window before a screenshot, in ms.
constexpr int kScreenshotSettleMs = 500;

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
  const QCommandLineOption cursor_option("cursor", "Place the readout cursor at <t> seconds.", "t");
  const QCommandLineOption window_option("window", "Show the time window <t0:t1> in seconds.",
                                         "t0:t1");
  const QCommandLineOption run_option(
      "run", "Run a fit or a diagnosis of the recordings in the panel first: fit | diagnose.",
      "job");
  parser.addOptions({screenshot_option, size_option, cursor_option, window_option, run_option});
  parser.process(app);

  const QString screenshot_path = parser.value(screenshot_option);
  const bool screenshot = !screenshot_path.isEmpty();
  oscilab::ui::MainWindow window;
  window.set_interactive_errors(!screenshot);

  const QStringList size = parser.value(size_option).split('x');
  if (screenshot && size.size() == 2) window.resize(size[0].toInt(), size[1].toInt());
  window.show();

  const QStringList recordings = parser.positionalArguments();
  bool opened = true;
  for (qsizetype i = recordings.size() - 1; i >= 0; --i) {  // the first ends up shown
    opened = window.open_recording(recordings[i]) && opened;
  }
  const QStringList window_s = parser.value(window_option).split(':');
  if (window_s.size() == 2) {
    window.record_view()->set_time_window(window_s[0].toDouble(), window_s[1].toDouble());
  }
  if (parser.isSet(cursor_option)) {
    window.record_view()->set_cursor_time(parser.value(cursor_option).toDouble());
  }
  if (!screenshot) return QApplication::exec();

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
  const QString job = parser.value(run_option);
  if (job == "fit" || job == "diagnose") {
    auto* panel = window.identification_panel();
    QObject::connect(panel, &oscilab::ui::IdentificationPanel::job_finished, &window, grab);
    if (job == "fit") {
      panel->start_fit();
    } else {
      panel->start_diagnosis();
    }
  } else {
    grab();
  }
  QApplication::exec();
  return status;
}

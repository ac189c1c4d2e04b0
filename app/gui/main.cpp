// oscilab: the desktop app. `oscilab [REC...]` opens a window on recordings (the first is shown,
// all are analysed for the review, and those not of a random or other non-stepped test join the fit
// and diagnosis panel); `oscilab --session FILE`
// opens a saved session. The view options (--cursor T, --window T0:T1, --level R:L,...,
// --tab levels|cycles|rfs|annotations, --mark T:NOTE, --hide-panel, --theme dark) set up what the
// window shows;
// `--screenshot OUT.png ...` runs the app as a script for a picture of it (window_script.h).
#include <cstdio>
#include <memory>
#include <vector>

#include <QApplication>
#include <QCommandLineParser>
#include <QDockWidget>
#include <QMenu>
#include <QStatusBar>
#include <QTabWidget>

#include "app/gui/window_script.h"
#include "ui/main_window.h"
#include "ui/review/record_view.h"
#include "ui/review/review_view.h"

namespace {

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
  const QCommandLineOption theme_option(
      "theme", "Colour scheme, as View > Theme: system | light | dark.", "theme");
  parser.addOptions({session_option, cursor_option, window_option, level_option, tab_option,
                     mark_option, hide_panel_option, theme_option});
  oscilab::gui::WindowScript::add_options(parser);
  parser.process(app);

  oscilab::gui::WindowScript script(parser);
  oscilab::ui::MainWindow window;
  window.set_interactive_errors(!script.active());
  oscilab::ui::ReviewView* review = window.review_view();
  if (script.active()) script.size_window(window);
  if (parser.isSet(hide_panel_option)) {
    if (auto* dock = window.findChild<QDockWidget*>("identification_dock")) dock->hide();
  }
  if (auto* themes = window.findChild<QMenu*>("theme_menu"); themes && parser.isSet(theme_option)) {
    const int index = QStringList{"system", "light", "dark"}.indexOf(parser.value(theme_option));
    if (index >= 0) themes->actions().at(index)->trigger();
  }
  window.show();
  if (script.active()) script.prepare(window);

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

  if (!script.active()) {
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
  if (script.picture_taken()) return script.status();
  if (!opened) {
    std::fprintf(stderr, "oscilab: %s\n", qPrintable(window.statusBar()->currentMessage()));
    return 1;
  }
  return script.run(window, analysing, apply_view);
}

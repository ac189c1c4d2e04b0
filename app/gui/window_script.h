#pragma once

#include <functional>

#include <QCommandLineParser>
#include <QString>
#include <QStringList>

namespace oscilab::ui {
class MainWindow;
}

namespace oscilab::gui {

/// The app run as a script, for pictures of it (the README's screenshots, scripts/screenshot.sh):
/// `--screenshot OUT.png [--size WxH] [--run fit|diagnose [--dialog hbm|map|figures]
/// [--panel-tab NAME]] [--live rig|REC] [--dialog mapping]` opens the window, does what is asked,
/// saves a picture of the window (or of the dialog) once everything asked has finished, and exits.
/// Kept apart from the app's own start-up, which only opens the window on recordings or a session.
class WindowScript {
 public:
  /// Adds the script's options to the app's parser.
  static void add_options(QCommandLineParser& parser);

  /// Reads the options from a parser that has processed the command line.
  explicit WindowScript(const QCommandLineParser& parser);

  /// --screenshot given: the app runs as this script.
  bool active() const { return !screenshot_path_.isEmpty(); }
  /// Resizes `window` to --size (1280x800 by default).
  void size_window(QWidget& window) const;
  /// Before the recordings open: with --dialog mapping, the picture is of the channel mapping
  /// dialog the first recording without a sidecar brings up (nothing is written beside it).
  void prepare(ui::MainWindow& window);
  /// The picture was taken while the recordings opened (--dialog mapping); run() has no more
  /// to do.
  bool picture_taken() const { return picture_taken_; }
  int status() const { return status_; }

  /// Runs the script on the opened window: starts the job (--run) or the live source (--live),
  /// waits for the analysis (when `analysing`), the job and 7 s of the live source, applies
  /// `apply_view` once the analysis is shown, saves the picture and returns the exit status
  /// (0, or 1 when something could not be done or written, said on stderr).
  int run(ui::MainWindow& window, bool analysing, const std::function<void()>& apply_view);

 private:
  QString screenshot_path_;
  QStringList size_;
  bool size_given_ = false;
  QString job_;
  QString dialog_;
  QString panel_tab_;
  QString live_source_;
  QString adaptive_rig_;
  QString adaptive_effects_;
  bool picture_taken_ = false;
  int status_ = 0;
};

}  // namespace oscilab::gui

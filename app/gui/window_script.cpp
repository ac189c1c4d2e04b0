#include "app/gui/window_script.h"

#include <cstdio>
#include <memory>
#include <optional>

#include <QApplication>
#include <QCheckBox>
#include <QDir>
#include <QEventLoop>
#include <QLabel>
#include <QLineEdit>
#include <QTabWidget>
#include <QTimer>

#include <qcustomplot.h>

#include "ui/identification/figure_dialog.h"
#include "ui/identification/identification_panel.h"
#include "ui/identification/response_dialog.h"
#include "ui/live/adaptive_test_panel.h"
#include "ui/live/live_monitor.h"
#include "ui/live/live_settings.h"
#include "ui/main_window.h"
#include "ui/review/channel_mapping_dialog.h"
#include "ui/review/record_view.h"

namespace oscilab::gui {
namespace {

// Time the event loop gets to lay out and paint the window before a picture, in ms.
constexpr int kSettleMs = 500;
// How long the live source runs before its picture, in ms: at 20× the rig's 6 s levels reach the
// 23rd.
constexpr int kLiveMs = 7000;

}  // namespace

void WindowScript::add_options(QCommandLineParser& parser) {
  parser.addOptions({
      {"screenshot", "Save a PNG of the window to <png> and exit (no dialogs).", "png"},
      {"size", "Window size for --screenshot (default 1280x800).", "WxH", "1280x800"},
      {"run",
       "With --screenshot: run a fit or a diagnosis of the recordings first: fit | diagnose.",
       "job"},
      {"dialog",
       "With --run fit and --screenshot: open a dialog of the fit panel once the fit ended and "
       "save its picture instead: hbm (the HBM branches) | map (the bifurcation map) | figures. "
       "Without --run: mapping (the dialog File > Open shows for a file without a sidecar).",
       "dialog"},
      {"panel-tab",
       "With --run and --screenshot: the fit panel's tab the picture shows once the job ended, "
       "by its name, e.g. \"Missing energy\" (default: the one the job shows).",
       "name"},
      {"live",
       "With --screenshot: show the Live tab running <source>: rig (the virtual rig stepping "
       "0.2 to 2.7 N at 20x) or a recording to replay at 10x; the picture is taken after 7 s.",
       "source"},
      {"adaptive",
       "With --screenshot: run the Live tab's adaptive test on a virtual rig of <rig-model> "
       "(paper or a model JSON) in Auto until its third decision; the picture shows the fourth "
       "decision's proposal waiting for the operator (or the end of the test, if it comes "
       "first). Its folder is a temporary one.",
       "rig-model"},
      {"effects", "With --adaptive: the candidate effects weighed, comma-separated (default: all).",
       "list"},
  });
}

WindowScript::WindowScript(const QCommandLineParser& parser)
    : screenshot_path_(parser.value("screenshot")),
      size_(parser.value("size").split('x')),
      size_given_(parser.isSet("size")),
      job_(parser.value("run")),
      dialog_(parser.value("dialog")),
      panel_tab_(parser.value("panel-tab")),
      live_source_(parser.value("live")),
      adaptive_rig_(parser.value("adaptive")),
      adaptive_effects_(parser.value("effects")) {}

void WindowScript::prepare(ui::MainWindow& window) {
  if (dialog_ != "mapping") return;
  window.set_mapping_asker([this](const QString& path, const daq::FileContents& contents) {
    ui::ChannelMappingDialog dialog(path, contents);
    if (size_given_) size_window(dialog);
    dialog.show();
    QEventLoop settle;
    QTimer::singleShot(kSettleMs, &settle, &QEventLoop::quit);
    settle.exec();
    if (!dialog.grab().save(screenshot_path_)) {
      std::fprintf(stderr, "oscilab: cannot write %s\n", qPrintable(screenshot_path_));
      status_ = 1;
    }
    picture_taken_ = true;
    return std::optional<daq::Sidecar>();
  });
}

void WindowScript::size_window(QWidget& window) const {
  if (size_.size() == 2) window.resize(size_[0].toInt(), size_[1].toInt());
}

int WindowScript::run(ui::MainWindow& window, bool analysing,
                      const std::function<void()>& apply_view) {
  int status = 0;
  const auto save = [&](QWidget* shown) {
    QTimer::singleShot(kSettleMs, &window, [&, shown] {
      if (shown == &window) window.record_view()->plot()->replot();
      if (shown == nullptr || !shown->grab().save(screenshot_path_)) {
        std::fprintf(stderr, "oscilab: cannot write %s\n", qPrintable(screenshot_path_));
        status = 1;
      }
      QApplication::quit();
    });
  };
  // The picture waits for the analysis, the job and the live source, whichever ends last.
  const bool run_job = job_ == "fit" || job_ == "diagnose";
  int waiting = (analysing ? 1 : 0) + (run_job ? 1 : 0);
  const auto done = [&] {
    if (--waiting == 0) save(&window);
  };
  bool analysed = false;
  if (analysing) {
    QObject::connect(&window, &ui::MainWindow::analysis_finished, &window, [&] {
      if (analysed) return;  // the picture shows the first analysis
      analysed = true;
      apply_view();
      done();
    });
  }
  // --dialog: once the fit ended, the dialog is opened and computed, and its picture taken.
  const auto save_dialog = [&](QWidget* shown) {
    if (shown != nullptr && size_given_) size_window(*shown);  // --size is the dialog's
    save(shown);
  };
  auto* panel = window.identification_panel();
  const auto open_dialog = [&] {
    if (dialog_ == "figures") {
      QObject::connect(panel, &ui::IdentificationPanel::figures_shown, &window,
                       [&] { save_dialog(panel->figures_dialog()); });
      panel->show_figures();
      return;
    }
    ui::ResponseDialog* shown =
        dialog_ == "map" ? panel->open_map_dialog() : panel->open_branch_dialog();
    if (shown == nullptr) {
      save_dialog(nullptr);
      return;
    }
    QObject::connect(shown, &ui::ResponseDialog::computed, &window,
                     [&, shown] { save_dialog(shown); });
  };
  if (run_job) {
    QObject::connect(panel, &ui::IdentificationPanel::job_finished, &window, [&] {
      if (dialog_.isEmpty() || job_ != "fit") {
        QTabWidget* tabs = panel->tabs();
        for (int i = 0; i < tabs->count(); ++i) {
          if (tabs->tabText(i) == panel_tab_) tabs->setCurrentIndex(i);
        }
        done();
      } else {
        open_dialog();
      }
    });
    if (job_ == "fit") {
      panel->start_fit();
    } else {
      panel->start_diagnosis();
    }
  }
  if (!live_source_.isEmpty()) {
    ui::LiveMonitor* live = window.live_monitor();
    window.central_tabs()->setCurrentWidget(live);
    ui::LiveSettings settings = live->settings();
    const bool rig = live_source_ == "rig";
    settings.source = rig ? ui::LiveSourceKind::Rig : ui::LiveSourceKind::Replay;
    settings.replay_path = live_source_.toStdString();
    settings.speed = rig ? 20.0 : 10.0;
    live->set_settings(settings);
    if (rig) live->set_rig_schedule(ui::stepped_schedule(0.2, 2.7, 0.1, 6, 1, 9));  // §3.2
    if (!live->start()) {
      std::fprintf(stderr, "oscilab: %s\n", qPrintable(live->message()));
      return 1;
    }
    ++waiting;
    QTimer::singleShot(kLiveMs, &window, done);
  }
  if (!adaptive_rig_.isEmpty()) {
    ui::LiveMonitor* live = window.live_monitor();
    window.central_tabs()->setCurrentWidget(live);
    live->views()->setCurrentWidget(live->adaptive_test());
    ui::AdaptiveTestPanel* test = live->adaptive_test();
    test->rig_truth_edit()->setText(adaptive_rig_);
    test->effects_edit()->setText(adaptive_effects_);
    test->folder_edit()->setText(QDir::temp().filePath(
        QStringLiteral("oscilab-adaptive-screenshot-%1").arg(QCoreApplication::applicationPid())));
    test->auto_box()->setChecked(true);
    // Auto until the third decision; the fourth's proposal then waits for the operator.
    QObject::connect(test->job(), &ui::AdaptiveTestJob::decided, &window, [test] {
      if (test->steps().size() == 3) test->auto_box()->setChecked(false);
    });
    const auto taken = std::make_shared<bool>(false);
    const auto picture = [&, taken] {
      if (*taken) return;
      *taken = true;
      done();
    };
    QObject::connect(test->job(), &ui::AdaptiveTestJob::awaiting_changed, &window,
                     [picture](bool awaiting) {
                       if (awaiting) picture();
                     });
    QObject::connect(test, &ui::AdaptiveTestPanel::test_finished, &window, picture);
    if (!test->start()) {
      std::fprintf(stderr, "oscilab: %s\n", qPrintable(test->verdict_label()->text()));
      return 1;
    }
    ++waiting;
  }
  if (waiting == 0) save(&window);
  QApplication::exec();
  return status;
}

}  // namespace oscilab::gui

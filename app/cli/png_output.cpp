#include "app/cli/png_output.h"

#include <cstdlib>
#include <memory>

#include "analysis/common/input_error.h"

#ifdef OSCILAB_CLI_WITH_GUI
#include <QApplication>
#include <QByteArray>

#include "ui/figure_renderer.h"
#endif

namespace oscilab::cli {

#ifdef OSCILAB_CLI_WITH_GUI

bool png_output_available() { return true; }

void write_figure_png(const ui::Figure& figure, const std::string& path) {
  // One application for the process, made only when a figure is asked for, so that the other
  // commands never touch Qt. Without a display Qt would abort; the offscreen platform renders
  // into memory, which is all savePng needs.
  static int argc = 1;
  static char name[] = "oscilab-cli";
  static char* argv[] = {name, nullptr};
  static std::unique_ptr<QApplication> app;
  if (!app) {
    if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr &&
        !qEnvironmentVariableIsSet("QT_QPA_PLATFORM")) {
      qputenv("QT_QPA_PLATFORM", QByteArray("offscreen"));
    }
    app = std::make_unique<QApplication>(argc, argv);
  }
  const std::string error = ui::render_figure_png(figure, path);
  if (!error.empty()) throw InputError(error);
}

#else

bool png_output_available() { return false; }

void write_figure_png(const ui::Figure&, const std::string& path) {
  throw InputError("--png: cannot write " + path +
                   ": this oscilab-cli was built without the GUI (OSCILAB_BUILD_GUI=OFF), and PNG "
                   "figures need Qt; the CSV files hold the same data");
}

#endif

}  // namespace oscilab::cli

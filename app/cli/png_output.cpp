#include "app/cli/png_output.h"

#include <cstdlib>

#include "analysis/common/input_error.h"

#ifdef OSCILAB_CLI_WITH_GUI
#include <QApplication>
#include <QByteArray>

#include "ui/figure_renderer.h"
#endif

namespace oscilab::cli {

#ifdef OSCILAB_CLI_WITH_GUI

struct FigureWriter::Application {
  int argc = 1;
  char name[16] = "oscilab-cli";
  char* argv[2] = {name, nullptr};
  QApplication app{argc, argv};  // QApplication keeps references to argc and argv
};

FigureWriter::FigureWriter() {
  // Without a display Qt's default platform would abort; the offscreen platform renders into
  // memory, which is all QCustomPlot::savePng needs.
  if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr &&
      !qEnvironmentVariableIsSet("QT_QPA_PLATFORM")) {
    qputenv("QT_QPA_PLATFORM", QByteArray("offscreen"));
  }
  app_ = std::make_unique<Application>();
}

void FigureWriter::write(const ui::Figure& figure, const std::string& path) {
  const std::string error = ui::render_figure_png(figure, path);
  if (!error.empty()) throw InputError(error);
}

#else

struct FigureWriter::Application {};

FigureWriter::FigureWriter() {
  throw InputError(
      "--png: this oscilab-cli was built without the GUI (OSCILAB_BUILD_GUI=OFF), and PNG "
      "figures need Qt; the CSV files hold the same data");
}

void FigureWriter::write(const ui::Figure&, const std::string&) {}

#endif

FigureWriter::~FigureWriter() = default;

}  // namespace oscilab::cli

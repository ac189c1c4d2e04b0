#pragma once

#include <memory>
#include <string>

#include "ui/figure.h"

namespace oscilab::cli {

/// Writes figures as PNG (ui::render_figure_png). Owns the QApplication the renderer needs for
/// its lifetime, made with the "offscreen" platform when no display is set, so that the other
/// commands never touch Qt. Construct it only when figures are asked for; one at a time.
class FigureWriter {
 public:
  /// Throws InputError when the CLI was built without the GUI (OSCILAB_BUILD_GUI=OFF).
  FigureWriter();
  ~FigureWriter();
  FigureWriter(const FigureWriter&) = delete;
  FigureWriter& operator=(const FigureWriter&) = delete;

  /// Throws InputError when the file cannot be written.
  void write(const ui::Figure& figure, const std::string& path);

 private:
  struct Application;
  std::unique_ptr<Application> app_;
};

}  // namespace oscilab::cli

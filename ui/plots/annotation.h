#pragma once

#include <string>

namespace oscilab::ui {

/// A note a person puts on a recording at a time (Review ▸ Mark, Ctrl+M), drawn as a labelled
/// vertical line on the time plots and saved with the session. Qt-free.
struct Annotation {
  std::string recording;  // path of the recording it belongs to (absolute, as opened)
  double t_s = 0.0;       // time in that recording
  std::string text;

  bool operator==(const Annotation&) const = default;
};

}  // namespace oscilab::ui

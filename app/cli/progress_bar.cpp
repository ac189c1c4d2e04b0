#include "app/cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace oscilab::cli {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), enabled_(isatty(fileno(stderr)) != 0) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && last_percent_ >= 0) std::fputc('\n', stderr);
}

ProgressFn ProgressBar::callback() {
  return [this](double fraction) { draw(fraction); };
}

void ProgressBar::show(double fraction, const std::string& detail) {
  if (!enabled_) return;
  const int percent = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100.0);
  if (percent == last_percent_ && detail == detail_) return;
  last_percent_ = percent;
  detail_ = detail;
  constexpr int kWidth = 40;
  const int filled = percent * kWidth / 100;
  // \033[K clears what a longer text drawn before left at the end of the line.
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%%s%s\033[K", label_.c_str(), filled,
               "########################################", kWidth - filled, "", percent,
               detail_.empty() ? "" : "  ", detail_.c_str());
  std::fflush(stderr);
}

}  // namespace oscilab::cli

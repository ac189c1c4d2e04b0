#pragma once

#include <string>

#include <QString>

namespace oscilab::ui {

/// The core's UTF-8 text (names, units, messages) as a QString.
inline QString qtext(const std::string& utf8) { return QString::fromStdString(utf8); }

}  // namespace oscilab::ui

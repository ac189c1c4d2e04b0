#pragma once

#include <cmath>

#include <nlohmann/json.hpp>

namespace oscilab {

/// A number for a JSON report: JSON has no NaN or infinity, so such values are written as null.
inline nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace oscilab

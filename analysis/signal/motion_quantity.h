#pragma once

#include <string>

namespace oscilab::analysis {

/// What a motion channel measures (its SI unit is m, m/s or m/s²).
enum class MotionQuantity { Displacement, Velocity, Acceleration };

/// Derivative order of a quantity relative to displacement: 0, 1, 2.
inline int derivative_order(MotionQuantity quantity) {
  switch (quantity) {
    case MotionQuantity::Displacement:
      return 0;
    case MotionQuantity::Velocity:
      return 1;
    case MotionQuantity::Acceleration:
      return 2;
  }
  return 0;
}

inline std::string to_string(MotionQuantity quantity) {
  switch (quantity) {
    case MotionQuantity::Displacement:
      return "displacement";
    case MotionQuantity::Velocity:
      return "velocity";
    case MotionQuantity::Acceleration:
      return "acceleration";
  }
  return "?";
}

}  // namespace oscilab::analysis

#pragma once

#include <QColor>

#include "analysis/edc/well.h"

namespace oscilab::ui {

/// The colour of a well in every review plot (Fig. 9: blue around z₊*, orange around z₋*;
/// Okabe–Ito's colour-blind-safe blue and vermilion, as the fit panel draws them), grey for
/// cross-well or unknown motion.
inline QColor well_colour(analysis::Well well) {
  if (well == analysis::Well::Positive) return {0, 114, 178};
  if (well == analysis::Well::Negative) return {213, 94, 0};
  return {110, 110, 110};
}

}  // namespace oscilab::ui

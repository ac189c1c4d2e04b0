#pragma once

#include <QDoubleSpinBox>
#include <QString>

namespace oscilab::ui {

/// A spin box for a number in [low, high] with `decimals`, `step` and a unit `suffix`.
inline QDoubleSpinBox* number_box(double low, double high, double value, int decimals, double step,
                                  const QString& suffix) {
  auto* box = new QDoubleSpinBox;
  box->setRange(low, high);
  box->setDecimals(decimals);
  box->setSingleStep(step);
  box->setValue(value);
  box->setSuffix(suffix);
  return box;
}

}  // namespace oscilab::ui

#pragma once

#include <cmath>

#include <QString>
#include <QTableWidgetItem>

namespace oscilab::ui {

/// A read-only table cell with the given text.
inline QTableWidgetItem* read_only_cell(const QString& text) {
  auto* item = new QTableWidgetItem(text);
  item->setFlags(item->flags() & ~Qt::ItemIsEditable);
  return item;
}

/// A number with `digits` significant digits, "—" when it is not finite.
inline QString number_text(double value, int digits = 4) {
  return std::isfinite(value) ? QString::number(value, 'g', digits) : QStringLiteral("—");
}

}  // namespace oscilab::ui

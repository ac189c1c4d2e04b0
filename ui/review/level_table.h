#pragma once

#include <vector>

#include <QTableWidget>

#include "ui/review/review_model.h"

namespace oscilab::ui {

/// The level table of the record review: one row per stepped-sine level of every analysed
/// record (record, well, f₀ [N], EDC mean and std [mJ], steady cycles, flags), sortable by any
/// column (numbers sort as numbers). Selecting rows (several with Ctrl or Shift) emits
/// levels_selected. Rows are built by level_rows (review_model.h); the table only shows them.
class LevelTable : public QTableWidget {
  Q_OBJECT

 public:
  enum Column { kRecord, kWell, kF0, kEdcMean, kEdcStd, kCycles, kFlags, kColumnCount };
  /// Item data role holding a numeric cell's value in SI (f₀ in N, EDC in J, cycles).
  static constexpr int kValueRole = Qt::UserRole;

  explicit LevelTable(QWidget* parent = nullptr);

  /// Replaces the rows (the selection is cleared, the sort order kept). `force_unit` and
  /// `energy_unit` head the f₀ and EDC columns ("N", "mJ"; "N/kg", "mJ/kg" per unit mass).
  void set_rows(const std::vector<LevelRow>& rows, const QString& force_unit = QStringLiteral("N"),
                const QString& energy_unit = QStringLiteral("mJ"));
  /// The level shown in `row` (the view's row, after sorting).
  LevelKey key_at(int row) const;
  /// The view's row of `key`, or -1.
  int row_of(LevelKey key) const;
  /// The selected levels, the current row's first.
  std::vector<LevelKey> selected_levels() const;
  /// Selects the rows of `keys` (unknown keys are skipped), the first becoming current, and
  /// scrolls to it. Emits levels_selected once.
  void select_levels(const std::vector<LevelKey>& keys);

 Q_SIGNALS:
  /// The selection changed; the current row's level first (empty: nothing selected).
  void levels_selected(const std::vector<oscilab::ui::LevelKey>& keys);

 private:
  bool updating_ = false;
  QString header_force_unit_;
  QString header_energy_unit_;
};

}  // namespace oscilab::ui

#include "ui/review/level_table.h"

#include <QHeaderView>
#include <QItemSelection>

#include "ui/plots/well_colours.h"

namespace oscilab::ui {
namespace {

// Data roles of the record column's item: which level the row shows.
constexpr int kRecordRole = Qt::UserRole + 1;
constexpr int kLevelRole = Qt::UserRole + 2;

// A cell that sorts by its SI value rather than its text.
class NumberItem : public QTableWidgetItem {
 public:
  NumberItem(const QString& text, double value) : QTableWidgetItem(text) {
    setData(LevelTable::kValueRole, value);
    setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  }
  bool operator<(const QTableWidgetItem& other) const override {
    return data(LevelTable::kValueRole).toDouble() < other.data(LevelTable::kValueRole).toDouble();
  }
};

QTableWidgetItem* read_only(QTableWidgetItem* item) {
  item->setFlags(item->flags() & ~Qt::ItemIsEditable);
  return item;
}

}  // namespace

LevelTable::LevelTable(QWidget* parent) : QTableWidget(0, kColumnCount, parent) {
  setHorizontalHeaderLabels({tr("record"), tr("well"), tr("f\u2080 [N]"), tr("EDC mean [mJ]"),
                             tr("EDC std [mJ]"), tr("cycles"), tr("flags")});
  header_force_unit_ = QStringLiteral("N");
  header_energy_unit_ = QStringLiteral("mJ");
  horizontalHeaderItem(kF0)->setToolTip(tr("forcing amplitude: |F\u2081| of f = \u2212m b\u0308"));
  horizontalHeaderItem(kEdcMean)->setToolTip(
      tr("energy dissipated per cycle \u222e f dz, mean over the steady cycles (\u00a74.1)"));
  horizontalHeaderItem(kEdcStd)->setToolTip(tr("standard deviation over the steady cycles"));
  horizontalHeaderItem(kCycles)->setToolTip(tr("steady cycles used"));
  setSelectionBehavior(QAbstractItemView::SelectRows);
  setSelectionMode(QAbstractItemView::ExtendedSelection);
  setEditTriggers(QAbstractItemView::NoEditTriggers);
  setAlternatingRowColors(true);
  setWordWrap(false);
  verticalHeader()->hide();
  verticalHeader()->setDefaultSectionSize(fontMetrics().height() + 6);
  horizontalHeader()->setStretchLastSection(true);
  horizontalHeader()->setHighlightSections(false);
  // Sortable by a click on a header; until then the analysis's order (record by record).
  horizontalHeader()->setSortIndicator(-1, Qt::AscendingOrder);
  setSortingEnabled(true);
  connect(this, &QTableWidget::itemSelectionChanged, this, [this] {
    if (!updating_) Q_EMIT levels_selected(selected_levels());
  });
}

void LevelTable::set_rows(const std::vector<LevelRow>& rows, const QString& force_unit,
                          const QString& energy_unit) {
  if (force_unit != header_force_unit_ || energy_unit != header_energy_unit_) {
    header_force_unit_ = force_unit;
    header_energy_unit_ = energy_unit;
    horizontalHeaderItem(kF0)->setText(tr("f\u2080 [%1]").arg(force_unit));
    horizontalHeaderItem(kEdcMean)->setText(tr("EDC mean [%1]").arg(energy_unit));
    horizontalHeaderItem(kEdcStd)->setText(tr("EDC std [%1]").arg(energy_unit));
  }
  updating_ = true;
  const bool sorting = isSortingEnabled();
  setSortingEnabled(false);  // rows are filled in place, then sorted once
  clearContents();
  setRowCount(int(rows.size()));
  for (int r = 0; r < int(rows.size()); ++r) {
    const LevelRow& row = rows[std::size_t(r)];
    auto* record = read_only(new QTableWidgetItem(QString::fromStdString(row.record)));
    record->setData(kRecordRole, row.key.record);
    record->setData(kLevelRole, row.key.level);
    setItem(r, kRecord, record);
    auto* well = read_only(new QTableWidgetItem(QString::fromStdString(to_string(row.well))));
    well->setForeground(well_colour(row.well));
    setItem(r, kWell, well);
    setItem(r, kF0, read_only(new NumberItem(QString::number(row.f0_n, 'f', 3), row.f0_n)));
    setItem(
        r, kEdcMean,
        read_only(new NumberItem(QString::number(1e3 * row.edc_mean_j, 'f', 4), row.edc_mean_j)));
    setItem(r, kEdcStd,
            read_only(new NumberItem(QString::number(1e3 * row.edc_std_j, 'f', 4), row.edc_std_j)));
    setItem(r, kCycles, read_only(new NumberItem(QString::number(row.cycles), row.cycles)));
    auto* flags = read_only(new QTableWidgetItem(QString::fromStdString(row.flags)));
    if (!row.flags.empty()) flags->setForeground(QColor(180, 0, 0));
    setItem(r, kFlags, flags);
  }
  setSortingEnabled(sorting);
  resizeColumnsToContents();
  updating_ = false;
}

LevelKey LevelTable::key_at(int row) const {
  const QTableWidgetItem* record = item(row, kRecord);
  if (!record) return {};
  return {record->data(kRecordRole).toInt(), record->data(kLevelRole).toInt()};
}

int LevelTable::row_of(LevelKey key) const {
  for (int r = 0; r < rowCount(); ++r) {
    if (key_at(r) == key) return r;
  }
  return -1;
}

std::vector<LevelKey> LevelTable::selected_levels() const {
  std::vector<LevelKey> keys;
  const int current = currentRow();
  const QModelIndexList rows = selectionModel()->selectedRows();
  if (current >= 0 && selectionModel()->isRowSelected(current, QModelIndex())) {
    keys.push_back(key_at(current));
  }
  for (const QModelIndex& index : rows) {
    if (index.row() != current) keys.push_back(key_at(index.row()));
  }
  return keys;
}

void LevelTable::select_levels(const std::vector<LevelKey>& keys) {
  updating_ = true;
  clearSelection();
  QItemSelection selection;
  int first = -1;
  for (const LevelKey& key : keys) {
    const int row = row_of(key);
    if (row < 0) continue;
    if (first < 0) first = row;
    selection.select(model()->index(row, 0), model()->index(row, kColumnCount - 1));
  }
  if (first >= 0) {
    setCurrentCell(first, 0, QItemSelectionModel::NoUpdate);
    selectionModel()->select(selection, QItemSelectionModel::ClearAndSelect);
    scrollToItem(item(first, 0));
  }
  updating_ = false;
  Q_EMIT levels_selected(selected_levels());
}

}  // namespace oscilab::ui

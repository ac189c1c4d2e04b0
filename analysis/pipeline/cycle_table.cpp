#include "analysis/pipeline/cycle_table.h"

#include <cmath>

namespace oscilab::analysis {

std::vector<CycleTableRow> cycle_table_rows(const CampaignAnalysis& campaign) {
  std::vector<CycleTableRow> rows;
  for (const RecordAnalysis& record : campaign.records) {
    for (const CycleFit& cycle : record.cycles) rows.push_back({&record.name, &cycle});
  }
  return rows;
}

std::vector<CycleTableRow> cycle_table_rows(const std::vector<CycleFit>& cycles) {
  std::vector<CycleTableRow> rows;
  rows.reserve(cycles.size());
  for (const CycleFit& cycle : cycles) rows.push_back({nullptr, &cycle});
  return rows;
}

const std::vector<TableColumn<CycleTableRow>>& cycle_table_columns() {
  using Row = CycleTableRow;
  constexpr ColumnKind kReal = ColumnKind::Real;
  static const std::vector<TableColumn<Row>> columns = {
      {"record", "", ColumnKind::Text, nullptr, "the recording the cycle comes from",
       [](const Row& r) -> CellValue { return r.record ? *r.record : std::string(); }},
      {"start_s", "s", kReal, "%.6f", "the start of the cycle's window",
       [](const Row& r) -> CellValue { return r.cycle->start_s; }},
      {"end_s", "s", kReal, "%.6f", "the end of the cycle's window, one forcing period later",
       [](const Row& r) -> CellValue { return r.cycle->end_s; }},
      {"f0_n", "N", kReal, "%.6g", "|F1|, the amplitude of the force's first harmonic",
       [](const Row& r) -> CellValue { return r.cycle->f0_n; }},
      {"edc_j", "J", kReal, "%.9g",
       "the energy dissipated in the cycle, the loop integral of f dz from all fitted harmonics",
       [](const Row& r) -> CellValue { return r.cycle->edc_j; }},
      {"edc_eq13_j", "J", kReal, "%.9g",
       "the first-harmonic estimate of eq. (13), pi f0 |Z1| sin theta1",
       [](const Row& r) -> CellValue { return r.cycle->edc_eq13_j; }},
      {"edc_trapz_j", "J", kReal, "%.9g", "the trapezoidal loop area on the samples",
       [](const Row& r) -> CellValue { return r.cycle->edc_trapz_j; }},
      {"z1_abs_m", "m", kReal, "%.9g", "|Z1|, the amplitude of z's first harmonic",
       [](const Row& r) -> CellValue {
         return r.cycle->z_h.empty() ? 0.0 : std::abs(r.cycle->z_h.front());
       }},
      {"lag_rad", "rad", kReal, "%.9g",
       "theta1, the lag of z's first harmonic behind the force (docs/conventions.md)",
       [](const Row& r) -> CellValue { return r.cycle->lag_rad; }},
      {"z_mean_m", "m", kReal, "%.9g", "the mean of z over the cycle",
       [](const Row& r) -> CellValue { return r.cycle->z_mean_m; }},
      {"z_min_m", "m", kReal, "%.9g", "the least z of the fitted motion over the cycle",
       [](const Row& r) -> CellValue { return r.cycle->z_min_m; }},
      {"z_max_m", "m", kReal, "%.9g", "the greatest z of the fitted motion over the cycle",
       [](const Row& r) -> CellValue { return r.cycle->z_max_m; }},
  };
  return columns;
}

}  // namespace oscilab::analysis

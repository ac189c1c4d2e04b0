#include "analysis/pipeline/edc_table.h"

#include "analysis/edc/well.h"
#include "analysis/pipeline/result_units.h"

namespace oscilab::analysis {

std::vector<EdcTableRow> edc_table_rows(const CampaignAnalysis& campaign) {
  std::vector<EdcTableRow> rows;
  for (const RecordAnalysis& record : campaign.records) {
    for (const LevelResult& level : record.levels) {
      rows.push_back({record.name, level, level_flags(record, level)});
    }
  }
  return rows;
}

const std::vector<TableColumn<EdcTableRow>>& edc_table_columns() {
  using Row = EdcTableRow;
  constexpr ColumnKind kReal = ColumnKind::Real;
  constexpr ColumnKind kInteger = ColumnKind::Integer;
  static const std::vector<TableColumn<Row>> columns = {
      {"well", "", ColumnKind::Text, nullptr,
       "the stable equilibrium the motion stays around: positive, negative, cross-well or "
       "unknown; empty for a level without steady cycles",
       [](const Row& r) -> CellValue { return to_string(r.level.well); }},
      {"f0_n", "N", kReal, "%.6g", "the forcing amplitude measured at the level",
       [](const Row& r) -> CellValue { return r.level.f0_n; }},
      {"edc_mean_j", "J", kReal, "%.9g",
       "the energy dissipated per cycle, the loop integral of f dz, mean over the steady cycles",
       [](const Row& r) -> CellValue { return r.level.edc_mean_j; }},
      {"edc_std_j", "J", kReal, "%.6g", "the standard deviation of the steady cycles' EDC",
       [](const Row& r) -> CellValue { return r.level.edc_std_j; }},
      {"cycles", "", kInteger, nullptr, "the steady cycles that went into the mean",
       [](const Row& r) -> CellValue { return std::int64_t{r.level.cycles}; }},
      {"record", "", ColumnKind::Text, nullptr, "the recording the level comes from",
       [](const Row& r) -> CellValue { return r.record; }},
      {"edc_noise_floor_j", "J", kReal, "%.6g",
       "the standard deviation of edc_mean_j predicted from the sensors' noise",
       [](const Row& r) -> CellValue { return r.level.edc_noise_floor_j; }},
      {"edc_eq13_mean_j", "J", kReal, "%.9g",
       "the first-harmonic estimate of eq. (13), pi f0 |Z1| sin theta1, mean over the steady "
       "cycles",
       [](const Row& r) -> CellValue { return r.level.edc_eq13_mean_j; }},
      {"edc_trapz_mean_j", "J", kReal, "%.9g",
       "the trapezoidal loop area on the samples, mean over the steady cycles",
       [](const Row& r) -> CellValue { return r.level.edc_trapz_mean_j; }},
      {"z1_abs_m", "m", kReal, "%.9g", "|Z1|, the amplitude of z's first harmonic, mean",
       [](const Row& r) -> CellValue { return r.level.z1_abs_m; }},
      {"lag_rad", "rad", kReal, "%.9g",
       "theta1, the lag of z's first harmonic behind the force (docs/conventions.md), mean",
       [](const Row& r) -> CellValue { return r.level.lag_rad; }},
      {"z_mean_m", "m", kReal, "%.9g", "the mean of z over the steady cycles",
       [](const Row& r) -> CellValue { return r.level.z_mean_m; }},
      {"start_s", "s", kReal, "%.6f",
       "the start of the first steady cycle (of the sidecar's window for a level without "
       "cycles)",
       [](const Row& r) -> CellValue { return r.level.start_s; }},
      {"end_s", "s", kReal, "%.6f", "the end of the last cycle (of the window without cycles)",
       [](const Row& r) -> CellValue { return r.level.end_s; }},
      {"transient_cycles", "", kInteger, nullptr,
       "the cycles the steady-state test dropped before the steady ones",
       [](const Row& r) -> CellValue { return std::int64_t{r.level.transient_cycles}; }},
      {"period1_change", "", kReal, "%.6g",
       "the median relative change of the harmonics between consecutive cycles",
       [](const Row& r) -> CellValue { return r.level.period1_change; }},
      {"usable", "", ColumnKind::Flag, nullptr,
       "period-1, within one well and measured (no degenerate-data flag)",
       [](const Row& r) -> CellValue { return r.level.usable(); }},
      {"flags", "", ColumnKind::Text, nullptr,
       "empty, or ;-separated flags: not-period-1, cross-well, few-cycles, the degenerate-data "
       "flags, per-unit-mass",
       [](const Row& r) -> CellValue { return r.flags; }},
  };
  return columns;
}

}  // namespace oscilab::analysis

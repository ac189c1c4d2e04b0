#pragma once

#include <string>
#include <vector>

#include "analysis/edc/level_tracker.h"
#include "analysis/pipeline/offline_analysis.h"
#include "analysis/pipeline/table_column.h"

namespace oscilab::analysis {

/// One row of the EDC table (docs/contracts.md §3): a level with the record it comes from.
struct EdcTableRow {
  std::string record;  // the recording's name; may be empty (a live level)
  LevelResult level;
  std::string flags;  // level_flags: the level's, and per-unit-mass without a mass
};

/// Every level of every record of a campaign, in record then level order (the rows of
/// `oscilab-cli analyze --edc`).
std::vector<EdcTableRow> edc_table_rows(const CampaignAnalysis& campaign);

/// The columns of the EDC table, in the order `analyze --edc` writes them (a contract scripts
/// rely on: later columns only ever go after these). Units are SI for a record with `mass_kg`;
/// without it forces are N/kg and energies J/kg (flag per-unit-mass).
const std::vector<TableColumn<EdcTableRow>>& edc_table_columns();

}  // namespace oscilab::analysis

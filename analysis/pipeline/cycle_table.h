#pragma once

#include <string>
#include <vector>

#include "analysis/edc/cycle_fit.h"
#include "analysis/pipeline/offline_analysis.h"
#include "analysis/pipeline/table_column.h"

namespace oscilab::analysis {

/// One row of the cycle table (`analyze --cycles`): a fitted cycle with the record it comes
/// from. A view: both point into what the rows were made from, and live no longer than it.
struct CycleTableRow {
  const std::string* record = nullptr;  // the recording's name; nullptr: none (a live cycle)
  const CycleFit* cycle = nullptr;
};

/// Every fitted cycle of every record of a campaign, in record then time order.
std::vector<CycleTableRow> cycle_table_rows(const CampaignAnalysis& campaign);

/// `cycles` without a record (the live analysis's): `record` is nullptr.
std::vector<CycleTableRow> cycle_table_rows(const std::vector<CycleFit>& cycles);

/// The columns of the cycle table, in the order `analyze --cycles` writes them. Units are SI
/// for a record with `mass_kg`; without it forces are N/kg and energies J/kg.
const std::vector<TableColumn<CycleTableRow>>& cycle_table_columns();

}  // namespace oscilab::analysis

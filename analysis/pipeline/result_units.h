#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "analysis/pipeline/offline_analysis.h"

// How results are stated for a person: their units (per unit mass when a record has no mass) and
// the notes of a campaign, each said once. The CLI's report, the app's review and the exports
// all use these.
namespace oscilab::analysis {

/// Whether a campaign's forces and energies are absolute, per unit mass (no record gives a
/// mass: N/kg, J/kg), or mixed.
enum class MassBasis { Absolute, PerUnitMass, Mixed };
MassBasis mass_basis(const CampaignAnalysis& campaign);

/// `unit` per unit mass where the basis says so: "N" → "N/kg", "mJ" → "mJ/kg"; for a mixed
/// campaign "N (N/kg where flagged per-unit-mass)".
std::string result_unit(const std::string& unit, MassBasis basis);
std::string result_unit(const std::string& unit, bool per_unit_mass);

/// A level's flags as the EDC table writes them: the level's own, then "per-unit-mass" when its
/// record has no mass.
std::string level_flags(const RecordAnalysis& record, const LevelResult& level);

/// A note and the records it concerns, in the order the notes first appear.
struct SharedNote {
  std::string text;
  std::vector<std::string> records;
};
std::vector<SharedNote> shared_notes(const CampaignAnalysis& campaign);

/// "no mass_kg ... (all 5 records)", "... (v1.csv, v3.csv)", or the text alone for a campaign of
/// one record.
std::string note_text(const SharedNote& note, std::size_t record_count);

}  // namespace oscilab::analysis

#include "analysis/pipeline/result_units.h"

#include <algorithm>

namespace oscilab::analysis {

MassBasis mass_basis(const CampaignAnalysis& campaign) {
  const auto per_mass = std::count_if(campaign.records.begin(), campaign.records.end(),
                                      [](const RecordAnalysis& r) { return r.per_unit_mass; });
  if (per_mass == 0) return MassBasis::Absolute;
  if (per_mass == static_cast<std::ptrdiff_t>(campaign.records.size())) {
    return MassBasis::PerUnitMass;
  }
  return MassBasis::Mixed;
}

std::string result_unit(const std::string& unit, bool per_unit_mass) {
  return per_unit_mass ? unit + "/kg" : unit;
}

std::string result_unit(const std::string& unit, MassBasis basis) {
  switch (basis) {
    case MassBasis::Absolute:
      return unit;
    case MassBasis::PerUnitMass:
      return unit + "/kg";
    case MassBasis::Mixed:
      return unit + " (" + unit + "/kg where flagged per-unit-mass)";
  }
  return unit;
}

std::string level_flags(const RecordAnalysis& record, const LevelResult& level) {
  std::string flags = level.flags();
  if (record.per_unit_mass) flags += flags.empty() ? "per-unit-mass" : ";per-unit-mass";
  return flags;
}

std::vector<SharedNote> shared_notes(const CampaignAnalysis& campaign) {
  std::vector<SharedNote> notes;
  for (const RecordAnalysis& record : campaign.records) {
    for (const std::string& text : record.notes) {
      auto it = std::find_if(notes.begin(), notes.end(),
                             [&](const SharedNote& note) { return note.text == text; });
      if (it == notes.end()) {
        notes.push_back({text, {}});
        it = notes.end() - 1;
      }
      if (std::find(it->records.begin(), it->records.end(), record.name) == it->records.end()) {
        it->records.push_back(record.name);
      }
    }
  }
  return notes;
}

std::string note_text(const SharedNote& note, std::size_t record_count) {
  if (record_count <= 1) return note.text;
  if (note.records.size() == record_count) {
    return note.text + " (all " + std::to_string(record_count) + " records)";
  }
  std::string names;
  for (std::size_t i = 0; i < note.records.size(); ++i) {
    if (i == 6) {
      names += ", and " + std::to_string(note.records.size() - 6) + " more";
      break;
    }
    names += (i == 0 ? "" : ", ") + note.records[i];
  }
  return note.text + " (" + names + ")";
}

}  // namespace oscilab::analysis

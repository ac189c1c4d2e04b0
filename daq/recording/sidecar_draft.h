#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "daq/recording/format_reader.h"

namespace oscilab::daq {

/// A sidecar drafted from what a file holds, for a person to check and complete
/// (`oscilab-cli info FILE --draft-sidecar S.json`, the app's File ▸ Open of a file without one).
struct SidecarDraft {
  nlohmann::ordered_json sidecar;  // the draft, in the sidecar's key order
  /// What was guessed and what is missing, one line each ("channels[0].role: guessed "base" from
  /// the unit m/s^2 (the first acceleration)", "sample_rate_hz: the file does not state it").
  std::vector<std::string> notes;
  bool complete = false;  // every required field has a value (the draft parses as a sidecar)
};

/// Drafts a sidecar for the first signals of `contents` that look like a base acceleration and
/// a mass motion. The file's unit text, when it names a unit Oscilab knows (in any of the usual
/// spellings: "m/s²", "m/s/s", "mm/s", "µm"), gives the quantity and the unit with scale 1; other
/// units (volts, counts, none) become "V" with scale 1, a calibration the person must give. The
/// rate is the file's when it states one. Roles: the first acceleration is the base, the first
/// velocity or displacement the mass; otherwise the first two signals in file order.
SidecarDraft draft_sidecar(const FileContents& contents);

/// The unit text a file states, in the sidecar's spelling when it is a unit the sidecar knows
/// ("m/s²" → "m/s^2", "Volts" → "V"), else the text unchanged.
std::string sidecar_unit_spelling(const std::string& file_unit);

}  // namespace oscilab::daq

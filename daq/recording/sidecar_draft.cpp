#include "daq/recording/sidecar_draft.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <set>

#include "analysis/common/input_error.h"
#include "daq/recording/sidecar.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

std::string trimmed(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

// One signal, or one column of a matrix signal, that could become a channel.
struct Candidate {
  const FileSignal* signal = nullptr;
  int column = -1;
  std::optional<Quantity> quantity;
  std::string unit;  // in the sidecar's spelling
};

bool looks_like_time(const FileSignal& signal) {
  std::string name = signal.name.substr(signal.name.find_last_of('/') + 1);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name == "t" || name == "time" || name == "t_s" || name == "time_s" ||
         trimmed(signal.unit) == "s";
}

// A channel name from a signal name: its last path part, printable, unique, not "t_s"; the whole
// name where the name picks the signal (a CSV header).
std::string channel_name(const Candidate& candidate, bool whole, std::set<std::string>& used) {
  if (whole) {
    used.insert(candidate.signal->name);
    return candidate.signal->name;
  }
  std::string base = candidate.signal->name.substr(candidate.signal->name.find_last_of('/') + 1);
  for (char& c : base) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
  }
  base = trimmed(base);
  if (base.empty() || base == "t_s") base = "signal";
  if (candidate.column >= 0) base += "[" + std::to_string(candidate.column) + "]";
  std::string name = base;
  for (int k = 2; !used.insert(name).second; ++k) name = base + "_" + std::to_string(k);
  return name;
}

}  // namespace

std::string sidecar_unit_spelling(const std::string& file_unit) {
  const std::string unit = trimmed(file_unit);
  struct Spelling {
    const char* file;
    const char* sidecar;
  };
  static constexpr Spelling kSpellings[] = {
      {"m/s\u00b2", "m/s^2"},
      {"m/s/s", "m/s^2"},
      {"m/s**2", "m/s^2"},
      {"m s^-2", "m/s^2"},
      {"m/sec^2", "m/s^2"},
      {"m/sec\u00b2", "m/s^2"},
      {"mm/s\u00b2", "mm/s^2"},
      {"mm/s/s", "mm/s^2"},
      {"G", "g"},
      {"gn", "g"},
      {"m/sec", "m/s"},
      {"mm/sec", "mm/s"},
      {"\u03bcm/s", "um/s"},
      {"\u03bcm", "um"},
      {"Volts", "V"},
      {"Volt", "V"},
      {"volts", "V"},
      {"v", "V"},
      {"Newton", "N"},
      {"newton", "N"},
  };
  for (const Spelling& spelling : kSpellings) {
    if (unit == spelling.file) return spelling.sidecar;
  }
  return unit;
}

SidecarDraft draft_sidecar(const FileContents& contents) {
  SidecarDraft draft;
  std::vector<Candidate> candidates;
  const FileSignal* time = nullptr;
  for (const FileSignal& signal : contents.file_signals) {
    if (signal.sample_count < 2) continue;
    if (signal.columns == 1 && looks_like_time(signal)) {
      if (time == nullptr) time = &signal;
      continue;
    }
    const std::string unit = sidecar_unit_spelling(signal.unit);
    const std::optional<Quantity> quantity = unit_quantity(unit);
    for (std::int64_t c = 0; c < std::min<std::int64_t>(signal.columns, 64); ++c) {
      candidates.push_back(
          {&signal, signal.columns > 1 ? static_cast<int>(c) : -1, quantity, unit});
    }
  }

  auto first_of = [&](auto predicate, const Candidate* other) -> const Candidate* {
    for (const Candidate& candidate : candidates) {
      if (&candidate != other && predicate(candidate)) return &candidate;
    }
    return nullptr;
  };
  const Candidate* base =
      first_of([](const Candidate& c) { return c.quantity == Quantity::Acceleration; }, nullptr);
  const Candidate* mass = first_of(
      [](const Candidate& c) {
        return c.quantity == Quantity::Velocity || c.quantity == Quantity::Displacement;
      },
      base);
  const bool base_guessed_by_order = base == nullptr;
  const bool mass_guessed_by_order = mass == nullptr;
  if (base == nullptr) base = first_of([](const Candidate&) { return true; }, mass);
  if (mass == nullptr) mass = first_of([](const Candidate&) { return true; }, base);

  nlohmann::ordered_json& out = draft.sidecar;
  out["format"] = kSidecarFormat;
  bool complete = base != nullptr && mass != nullptr;
  std::optional<double> rate_hz;
  for (const Candidate* candidate : {base, mass}) {
    if (candidate != nullptr && candidate->signal->sample_rate_hz) {
      rate_hz = candidate->signal->sample_rate_hz;
      break;
    }
  }
  if (rate_hz) {
    // A rate from a printed increment (1 / 5e-6 s = 200000.0000000016 Hz) reads as meant.
    const double whole_hz = std::round(*rate_hz);
    if (std::abs(*rate_hz - whole_hz) <= 1e-9 * *rate_hz) rate_hz = whole_hz;
    out["sample_rate_hz"] = *rate_hz;
  } else {
    out["sample_rate_hz"] = nullptr;
    draft.notes.push_back("sample_rate_hz: the file does not state it; give it");
    complete = false;
  }
  out["mass_kg"] = nullptr;
  draft.notes.push_back(
      "mass_kg: not in the file; give it, or leave it out for forces and energies per unit mass");

  out["channels"] = nlohmann::ordered_json::array();
  std::set<std::string> used;
  const char* roles[] = {"base", "mass"};
  const Candidate* chosen[] = {base, mass};
  for (int i = 0; i < 2; ++i) {
    const Candidate* candidate = chosen[i];
    const std::string where = "channels[" + std::to_string(i) + "]";
    if (candidate == nullptr) {
      draft.notes.push_back(where + ": the file holds no further signal for the " + roles[i] +
                            " channel");
      continue;
    }
    nlohmann::ordered_json channel;
    channel["name"] = channel_name(*candidate, !contents.picked_by_source, used);
    channel["role"] = roles[i];
    const bool known = candidate->quantity.has_value();
    const Quantity quantity =
        known ? *candidate->quantity : (i == 0 ? Quantity::Acceleration : Quantity::Displacement);
    channel["quantity"] = to_string(quantity);
    channel["unit"] = known ? candidate->unit : std::string("V");
    channel["scale"] = 1.0;
    if (contents.picked_by_source) {
      channel["source"] = candidate->signal->name;
      if (candidate->column >= 0) channel["column"] = candidate->column;
    }
    const bool by_order = i == 0 ? base_guessed_by_order : mass_guessed_by_order;
    std::string note = where + ".role: " + roles[i] + ", guessed from ";
    note += by_order ? "the order of the signals in the file"
                     : "the unit " + candidate->unit + " (the first " + to_string(quantity) + ")";
    draft.notes.push_back(note);
    if (!known) {
      draft.notes.push_back(
          where + ".unit: the file says " +
          (candidate->signal->unit.empty() ? std::string("no unit")
                                           : in_quotes(candidate->signal->unit)) +
          "; \"V\" with scale 1 is a placeholder: give the quantity and the sensitivity");
    }
    out["channels"].push_back(std::move(channel));
  }
  if (time != nullptr && !contents.picked_by_source && time->properties.contains("column")) {
    out["csv"] = {{"header", true}, {"time_column", time->properties["column"]}};
    draft.notes.push_back("csv.time_column: " + in_quotes(time->name) + " looks like the time");
  } else if (time != nullptr && contents.picked_by_source) {
    out["time"] = {{"source", time->name}};
    draft.notes.push_back("time: " + in_quotes(time->name) + " looks like the time axis");
  }
  if (complete) {
    try {
      parse_sidecar(nlohmann::json(out), "draft");
    } catch (const InputError& error) {
      draft.notes.push_back(std::string("the draft is not yet a valid sidecar: ") + error.what());
      complete = false;
    }
  }
  draft.complete = complete;
  return draft;
}

}  // namespace oscilab::daq

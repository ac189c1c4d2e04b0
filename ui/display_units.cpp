#include "ui/display_units.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace oscilab::ui {
namespace {

struct Prefix {
  const char* symbol;
  double factor;
};

// The prefixed units of one SI unit in decreasing size. min_reading: the smallest number the
// axis may show in a unit before the next smaller one is taken. base: the unprefixed unit.
struct Ladder {
  const char* si_unit;
  std::array<Prefix, 4> prefixes;
  int count;
  int base;
  double min_reading;
};

constexpr std::array<Ladder, 4> kLadders = {{
    {"m", {{{"m", 1.0}, {"mm", 1e-3}, {"µm", 1e-6}, {"nm", 1e-9}}}, 4, 0, 1.0},
    {"m/s", {{{"m/s", 1.0}, {"mm/s", 1e-3}, {"µm/s", 1e-6}, {"", 0.0}}}, 3, 0, 1.0},
    {"m/s^2", {{{"m/s²", 1.0}, {"mm/s²", 1e-3}, {"", 0.0}, {"", 0.0}}}, 2, 0, 0.1},
    {"N", {{{"kN", 1e3}, {"N", 1.0}, {"mN", 1e-3}, {"µN", 1e-6}}}, 4, 1, 1.0},
}};

std::string pretty_symbol(const std::string& si_unit) {
  std::string symbol = si_unit;
  for (std::size_t at = symbol.find("^2"); at != std::string::npos; at = symbol.find("^2")) {
    symbol.replace(at, 2, "²");
  }
  return symbol;
}

// Decimals that give `max_display` (a magnitude in display units) 4 significant digits.
int decimals_for(double max_display) {
  if (!(max_display > 0.0) || !std::isfinite(max_display)) return 3;
  return std::clamp(3 - int(std::floor(std::log10(max_display))), 0, 9);
}

DisplayUnit make_unit(std::string symbol, double si_per_unit, double max_abs) {
  return {std::move(symbol), si_per_unit, decimals_for(max_abs / si_per_unit)};
}

}  // namespace

std::string si_unit_of(daq::Quantity quantity) {
  switch (quantity) {
    case daq::Quantity::Acceleration:
      return "m/s^2";
    case daq::Quantity::Velocity:
      return "m/s";
    case daq::Quantity::Displacement:
      return "m";
    case daq::Quantity::Force:
      return "N";
  }
  return "";
}

DisplayUnit choose_display_unit(const std::string& si_unit, double max_abs) {
  for (const Ladder& ladder : kLadders) {
    if (si_unit != ladder.si_unit) continue;
    const Prefix& base = ladder.prefixes[std::size_t(ladder.base)];
    if (!(max_abs > 0.0) || !std::isfinite(max_abs)) return make_unit(base.symbol, base.factor, 0);
    for (int i = 0; i < ladder.count; ++i) {
      const Prefix& prefix = ladder.prefixes[std::size_t(i)];
      if (max_abs / prefix.factor >= ladder.min_reading) {
        return make_unit(prefix.symbol, prefix.factor, max_abs);
      }
    }
    const Prefix& smallest = ladder.prefixes[std::size_t(ladder.count - 1)];
    return make_unit(smallest.symbol, smallest.factor, max_abs);
  }
  return make_unit(pretty_symbol(si_unit), 1.0, max_abs);
}

std::vector<DisplayUnit> choose_display_units(const daq::OpenedRecording& recording) {
  std::vector<DisplayUnit> units;
  const auto& channels = recording.sidecar.channels;
  units.reserve(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const auto column = static_cast<Eigen::Index>(c);
    const bool has_data = recording.overview && column < recording.overview->channel_count() &&
                          recording.sample_count() > 0;
    const double max_abs = has_data ? recording.overview->max_abs(column) : 0.0;
    units.push_back(choose_display_unit(si_unit_of(channels[c].quantity), max_abs));
  }
  return units;
}

std::string format_value(double value_si, const DisplayUnit& unit) {
  std::array<char, 64> buffer{};
  const double value = unit.to_display(value_si);
  // No "-0.000": a value that rounds to zero is shown without sign.
  const double shown = std::abs(value) < 0.5 * std::pow(10.0, -unit.decimals) ? 0.0 : value;
  std::snprintf(buffer.data(), buffer.size(), "%.*f", unit.decimals, shown);
  std::string text = buffer.data();
  if (!unit.symbol.empty()) text += " " + unit.symbol;
  return text;
}

}  // namespace oscilab::ui

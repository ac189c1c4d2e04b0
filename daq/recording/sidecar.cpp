#include "daq/recording/sidecar.h"

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <system_error>

#include <unistd.h>

#include "analysis/common/input_error.h"
#include "daq/recording/json_field.h"
#include "daq/recording/json_file.h"

namespace oscilab::daq {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// A sidecar is a few kilobytes; anything this large is not one, and reading it whole would only
// waste memory before failing.
constexpr std::uintmax_t kMaxSidecarBytes = 64u << 20;  // bytes

// Largest CSV column index a sidecar may name; far beyond any instrument, small enough for int.
constexpr std::int64_t kMaxColumn = 1'000'000;
constexpr std::int64_t kMaxSkipLines = 1'000'000;

// What a vibration test's sidecar can sensibly hold; outside, the value is a unit mistake or a
// corrupt file, and taken at its word it runs the analysis into overflow or unbounded work (a
// mass of 1e308 kg overflows every force; a rate of 1e300 Hz makes a cycle 1e300 samples long).
constexpr double kMinSampleRateHz = 1e-3;  // one sample in 1000 s: slower is no vibration record
constexpr double kMaxSampleRateHz = 1e8;   // 100 MHz: beyond any vibration acquisition system
constexpr double kMinMassKg = 1e-9;        // 1 µg: a MEMS proof mass
constexpr double kMaxMassKg = 1e6;         // 1000 t: beyond any shaking table's payload
// |scale| and |offset| of a channel, in its unit (per stored unit for the scale). The finest
// calibration in use is about a picometre per count (an interferometer's, in m: 1e-12); the
// coarsest turns a count or a volt into at most a few thousand units (a kN load cell, 10 g per
// volt). 1e12 leaves room for any unit and container: a full-scale 32-bit count (2e9) then
// reaches 2e21, and an energy, the product of two channels and the squared frequency, stays far
// inside the double's range (1e308), where 1e300 overflows it.
constexpr double kMinScale = 1e-12;
constexpr double kMaxScale = 1e12;
constexpr double kMaxOffset = 1e12;

// A number for a message: %g, so 1e+09 and 0.26 read as written.
std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

std::string quoted_excerpt(const std::string& text) { return json_excerpt(json(text)); }

// A positive number within [lo, hi] of `unit`: values outside are unit mistakes or corrupt files,
// which would otherwise run the analysis into overflow or unbounded work.
double bounded_number(const json& value, double lo, double hi, const char* unit,
                      const JsonField& field) {
  const double x = field.positive_number(value);
  if (x < lo || x > hi) {
    field.fail(json_excerpt(value) + " " + unit + " is outside the range this field can have (" +
               format_number(lo) + " to " + format_number(hi) + " " + unit + ")");
  }
  return x;
}

ChannelRole parse_role(const json& value, const JsonField& field) {
  const std::string text = field.string(value);
  if (text == "base") return ChannelRole::Base;
  if (text == "mass") return ChannelRole::Mass;
  if (text == "relative") return ChannelRole::Relative;
  if (text == "force") return ChannelRole::Force;
  field.fail("unknown role " + quoted_excerpt(text) + " (expected base, mass, relative or force)");
}

Quantity parse_quantity(const json& value, const JsonField& field) {
  const std::string text = field.string(value);
  if (text == "acceleration") return Quantity::Acceleration;
  if (text == "velocity") return Quantity::Velocity;
  if (text == "displacement") return Quantity::Displacement;
  if (text == "force") return Quantity::Force;
  field.fail("unknown quantity " + quoted_excerpt(text) +
             " (expected acceleration, velocity, displacement or force)");
}

bool has_control_character(const std::string& text) {
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
  }
  return false;
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

ChannelInfo parse_channel(const json& value, const JsonField& field) {
  const json& object = field.object(value);
  ChannelInfo channel;
  channel.name = (field / "name").string(field.require(object, "name"));
  if (channel.name.empty()) (field / "name").fail("must not be empty");
  if (has_control_character(channel.name) || is_blank(channel.name.front()) ||
      is_blank(channel.name.back())) {
    (field / "name")
        .fail("invalid name " + quoted_excerpt(channel.name) +
              " (no control characters, no leading or trailing spaces)");
  }
  if (channel.name == "t_s") {
    (field / "name").fail("\"t_s\" is reserved for the CSV time column");
  }
  channel.role = parse_role(field.require(object, "role"), field / "role");
  channel.quantity = parse_quantity(field.require(object, "quantity"), field / "quantity");
  if ((channel.role == ChannelRole::Force) != (channel.quantity == Quantity::Force)) {
    (field / "quantity")
        .fail("quantity " + quoted_excerpt(to_string(channel.quantity)) + " does not fit role " +
              quoted_excerpt(to_string(channel.role)) +
              " (a force channel measures a force, and only force channels do)");
  }
  channel.unit = (field / "unit").string(field.require(object, "unit"));
  unit_to_si(channel.unit, channel.quantity, (field / "unit").where());
  channel.scale = (field / "scale").finite_number(field.require(object, "scale"));
  if (channel.scale == 0.0) (field / "scale").fail("must not be zero");
  if (std::abs(channel.scale) < kMinScale || std::abs(channel.scale) > kMaxScale) {
    (field / "scale")
        .fail(format_number(channel.scale) + " is outside the magnitudes a calibration can have (" +
              format_number(kMinScale) + " to " + format_number(kMaxScale) + ", either sign)");
  }
  if (const json* offset = JsonField::find(object, "offset")) {
    channel.offset = (field / "offset").finite_number(*offset);
    if (std::abs(channel.offset) > kMaxOffset) {
      (field / "offset")
          .fail(format_number(channel.offset) +
                " is outside the offsets a calibration can have (at most " +
                format_number(kMaxOffset) + " in magnitude)");
    }
  }
  if (const json* sensor = JsonField::find(object, "sensor")) {
    channel.sensor = (field / "sensor").string(*sensor);
  }
  if (const json* source = JsonField::find(object, "source")) {
    channel.source = (field / "source").string(*source);
    if (channel.source.empty()) (field / "source").fail("must not be empty");
  }
  if (const json* column = JsonField::find(object, "column")) {
    channel.column = (field / "column").whole_number(*column, kMaxColumn);
  }
  if (const json* range = JsonField::find(object, "range"); range && !range->is_null()) {
    const JsonField here = field / "range";
    if (!range->is_array() || range->size() != 2) {
      here.fail("expected [min, max] in the channel's unit, got " + json_excerpt(*range));
    }
    const double lo = here[0].finite_number((*range)[0]);
    const double hi = here[1].finite_number((*range)[1]);
    if (!(lo < hi)) here.fail("min must be below max, got " + json_excerpt(*range));
    channel.range = std::make_pair(lo, hi);
  }
  if (const json* corner = JsonField::find(object, "ac_coupling_hz");
      corner && !corner->is_null()) {
    channel.ac_coupling_hz = (field / "ac_coupling_hz").positive_number(*corner);
  }
  if (const json* full_scale = JsonField::find(object, "full_scale_v");
      full_scale && !full_scale->is_null()) {
    channel.full_scale_v = (field / "full_scale_v").positive_number(*full_scale);
  }
  for (const auto& [key, item] : object.items()) {
    if (key != "name" && key != "role" && key != "quantity" && key != "unit" && key != "scale" &&
        key != "offset" && key != "sensor" && key != "source" && key != "column" &&
        key != "range" && key != "ac_coupling_hz" && key != "full_scale_v") {
      channel.extra[key] = item;
    }
  }
  return channel;
}

CsvLayout parse_csv(const json& value, const JsonField& field) {
  const json& object = field.object(value);
  CsvLayout layout;
  for (const auto& [key, item] : object.items()) {
    const JsonField here = field / key;
    if (key == "header") {
      if (!item.is_boolean()) here.fail("expected true or false, got " + json_excerpt(item));
      layout.header = item.get<bool>();
    } else if (key == "delimiter") {
      const std::string text = here.string(item);
      if (text.size() != 1) here.fail("expected one character, got " + json_excerpt(item));
      const char c = text[0];
      if (std::strchr("0123456789.+-eE\"\r\n", c) != nullptr || c == '\0') {
        here.fail("cannot split numbers on " + json_excerpt(item));
      }
      layout.delimiter = c;
    } else if (key == "skip_lines") {
      layout.skip_lines = here.whole_number(item, kMaxSkipLines);
    } else if (key == "time_column") {
      layout.time_column = here.whole_number(item, kMaxColumn);
    } else {
      here.fail("unknown key (expected header, delimiter, skip_lines or time_column)");
    }
  }
  return layout;
}

SignalTime parse_time(const json& value, const JsonField& field) {
  const json& object = field.object(value);
  SignalTime time;
  time.source = (field / "source").string(field.require(object, "source"));
  if (time.source.empty()) (field / "source").fail("must not be empty");
  for (const auto& [key, item] : object.items()) {
    if (key == "column") {
      time.column = (field / key).whole_number(item, kMaxColumn);
    } else if (key != "source") {
      (field / key).fail("unknown key (expected source or column)");
    }
  }
  return time;
}

ExcitationLevel parse_level(const json& value, const JsonField& field) {
  const json& object = field.object(value);
  ExcitationLevel level;
  level.f0_n = (field / "f0_n").finite_number(field.require(object, "f0_n"));
  if (level.f0_n < 0.0)
    (field / "f0_n").fail("expected a non-negative amplitude, got " + json_excerpt(object["f0_n"]));
  level.start_s = (field / "start_s").finite_number(field.require(object, "start_s"));
  level.end_s = (field / "end_s").finite_number(field.require(object, "end_s"));
  if (!(level.start_s < level.end_s)) {
    (field / "end_s")
        .fail("must come after start_s (" + json_excerpt(object["start_s"]) + "), got " +
              json_excerpt(object["end_s"]));
  }
  for (const auto& [key, item] : object.items()) {
    if (key != "f0_n" && key != "start_s" && key != "end_s") level.extra[key] = item;
  }
  return level;
}

Excitation parse_excitation(const json& value, const JsonField& field) {
  const json& object = field.object(value);
  Excitation excitation;
  if (const json* type = JsonField::find(object, "type")) {
    excitation.type = (field / "type").string(*type);
  }
  if (const json* frequency = JsonField::find(object, "frequency_hz");
      frequency && !frequency->is_null()) {
    excitation.frequency_hz = (field / "frequency_hz").positive_number(*frequency);
  }
  if (const json* levels = JsonField::find(object, "levels")) {
    if (!levels->is_array())
      (field / "levels").fail("expected an array, got " + json_excerpt(*levels));
    for (std::size_t i = 0; i < levels->size(); ++i) {
      const JsonField here = (field / "levels")[i];
      ExcitationLevel level = parse_level((*levels)[i], here);
      if (!excitation.levels.empty() && level.start_s < excitation.levels.back().end_s) {
        (here / "start_s")
            .fail("levels must follow each other in time; " +
                  json_excerpt((*levels)[i]["start_s"]) +
                  " is before the end of the previous level");
      }
      excitation.levels.push_back(std::move(level));
    }
  }
  for (const auto& [key, item] : object.items()) {
    if (key != "type" && key != "frequency_hz" && key != "levels") excitation.extra[key] = item;
  }
  return excitation;
}

std::vector<InvalidInterval> parse_invalid_intervals(const json& value, const JsonField& field) {
  if (!value.is_array()) field.fail("expected an array, got " + json_excerpt(value));
  std::vector<InvalidInterval> intervals;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const JsonField here = field[i];
    const json& object = here.object(value[i]);
    InvalidInterval interval;
    interval.start_s = (here / "start_s").finite_number(here.require(object, "start_s"));
    interval.end_s = (here / "end_s").finite_number(here.require(object, "end_s"));
    if (interval.end_s < interval.start_s) {
      (here / "end_s").fail("must not come before start_s, got " + json_excerpt(object["end_s"]));
    }
    if (!intervals.empty() && interval.start_s < intervals.back().start_s) {
      (here / "start_s")
          .fail("intervals must be in time order, got " + json_excerpt(object["start_s"]));
    }
    if (const json* reason = JsonField::find(object, "reason")) {
      interval.reason = (here / "reason").string(*reason);
    }
    intervals.push_back(std::move(interval));
  }
  return intervals;
}

struct UnitEntry {
  const char* name;
  Quantity quantity;
  double factor;  // SI per unit
};

// Standard gravity, 9.80665 m/s² exactly (CGPM 1901).
constexpr double kStandardGravity = 9.80665;  // m/s² per g

constexpr UnitEntry kUnits[] = {
    {"m/s^2", Quantity::Acceleration, 1.0},
    {"m/s2", Quantity::Acceleration, 1.0},
    {"mm/s^2", Quantity::Acceleration, 1e-3},
    {"g", Quantity::Acceleration, kStandardGravity},
    {"m/s", Quantity::Velocity, 1.0},
    {"mm/s", Quantity::Velocity, 1e-3},
    {"um/s", Quantity::Velocity, 1e-6},
    {"\u00b5m/s", Quantity::Velocity, 1e-6},
    {"m", Quantity::Displacement, 1.0},
    {"mm", Quantity::Displacement, 1e-3},
    {"um", Quantity::Displacement, 1e-6},
    {"\u00b5m", Quantity::Displacement, 1e-6},
    {"N", Quantity::Force, 1.0},
    {"kN", Quantity::Force, 1e3},
};

std::string units_for(Quantity quantity) {
  std::string list;
  for (const UnitEntry& entry : kUnits) {
    if (entry.quantity != quantity) continue;
    list += entry.name;
    list += ", ";
  }
  return list + "V";
}

ordered_json channel_to_json(const ChannelInfo& channel) {
  ordered_json out;
  out["name"] = channel.name;
  out["role"] = to_string(channel.role);
  out["quantity"] = to_string(channel.quantity);
  out["unit"] = channel.unit;
  out["scale"] = channel.scale;
  out["offset"] = channel.offset;
  if (!channel.sensor.empty()) out["sensor"] = channel.sensor;
  if (!channel.source.empty()) out["source"] = channel.source;
  if (channel.column >= 0) out["column"] = channel.column;
  if (channel.range) out["range"] = {channel.range->first, channel.range->second};
  if (channel.ac_coupling_hz) out["ac_coupling_hz"] = *channel.ac_coupling_hz;
  if (channel.full_scale_v) out["full_scale_v"] = *channel.full_scale_v;
  if (channel.extra.is_object()) {
    for (const auto& [key, item] : channel.extra.items()) {
      if (!out.contains(key)) out[key] = item;
    }
  }
  return out;
}

ordered_json excitation_to_json(const Excitation& excitation) {
  ordered_json out = ordered_json::object();
  if (!excitation.type.empty()) out["type"] = excitation.type;
  if (excitation.frequency_hz) out["frequency_hz"] = *excitation.frequency_hz;
  if (!excitation.levels.empty()) {
    ordered_json levels = ordered_json::array();
    for (const ExcitationLevel& level : excitation.levels) {
      ordered_json item;
      item["f0_n"] = level.f0_n;
      item["start_s"] = level.start_s;
      item["end_s"] = level.end_s;
      if (level.extra.is_object()) {
        for (const auto& [key, value] : level.extra.items()) {
          if (!item.contains(key)) item[key] = value;
        }
      }
      levels.push_back(std::move(item));
    }
    out["levels"] = std::move(levels);
  }
  if (excitation.extra.is_object()) {
    for (const auto& [key, item] : excitation.extra.items()) {
      if (!out.contains(key)) out[key] = item;
    }
  }
  return out;
}

// The sidecar with its keys in the contract's order, so that written files read well.
ordered_json to_ordered_json(const Sidecar& sidecar) {
  ordered_json out;
  out["format"] = kSidecarFormat;
  out["sample_rate_hz"] = sidecar.sample_rate_hz;
  if (sidecar.mass_kg) out["mass_kg"] = *sidecar.mass_kg;
  ordered_json channels = ordered_json::array();
  for (const ChannelInfo& channel : sidecar.channels) channels.push_back(channel_to_json(channel));
  out["channels"] = std::move(channels);
  if (sidecar.csv) {
    ordered_json csv;
    csv["header"] = sidecar.csv->header;
    csv["delimiter"] = std::string(1, sidecar.csv->delimiter);
    if (sidecar.csv->skip_lines != 0) csv["skip_lines"] = sidecar.csv->skip_lines;
    if (sidecar.csv->time_column >= 0) csv["time_column"] = sidecar.csv->time_column;
    out["csv"] = std::move(csv);
  }
  if (sidecar.time) {
    ordered_json time;
    time["source"] = sidecar.time->source;
    if (sidecar.time->column >= 0) time["column"] = sidecar.time->column;
    out["time"] = std::move(time);
  }
  if (sidecar.excitation) out["excitation"] = excitation_to_json(*sidecar.excitation);
  if (!sidecar.notes.empty()) out["notes"] = sidecar.notes;
  if (!sidecar.invalid_intervals.empty()) {
    ordered_json intervals = ordered_json::array();
    for (const InvalidInterval& interval : sidecar.invalid_intervals) {
      ordered_json item;
      item["start_s"] = interval.start_s;
      item["end_s"] = interval.end_s;
      if (!interval.reason.empty()) item["reason"] = interval.reason;
      intervals.push_back(std::move(item));
    }
    out["invalid_intervals"] = std::move(intervals);
  }
  if (sidecar.extra.is_object()) {
    for (const auto& [key, item] : sidecar.extra.items()) {
      if (!out.contains(key)) out[key] = item;
    }
  }
  return out;
}

}  // namespace

std::string to_string(ChannelRole role) {
  switch (role) {
    case ChannelRole::Base:
      return "base";
    case ChannelRole::Mass:
      return "mass";
    case ChannelRole::Relative:
      return "relative";
    case ChannelRole::Force:
      return "force";
  }
  return "unknown";
}

std::string to_string(Quantity quantity) {
  switch (quantity) {
    case Quantity::Acceleration:
      return "acceleration";
    case Quantity::Velocity:
      return "velocity";
    case Quantity::Displacement:
      return "displacement";
    case Quantity::Force:
      return "force";
  }
  return "unknown";
}

std::string si_unit(Quantity quantity) {
  switch (quantity) {
    case Quantity::Acceleration:
      return "m/s^2";
    case Quantity::Velocity:
      return "m/s";
    case Quantity::Displacement:
      return "m";
    case Quantity::Force:
      return "N";
  }
  return "?";
}

std::optional<Quantity> unit_quantity(const std::string& unit) {
  for (const UnitEntry& entry : kUnits) {
    if (unit == entry.name) return entry.quantity;
  }
  return std::nullopt;
}

double unit_to_si(const std::string& unit, Quantity quantity, const std::string& where) {
  if (unit == "V") return 1.0;  // scale is the sensitivity in SI units per volt
  const UnitEntry* known = nullptr;
  for (const UnitEntry& entry : kUnits) {
    if (unit == entry.name) {
      known = &entry;
      if (entry.quantity == quantity) return entry.factor;
    }
  }
  const std::string prefix = where.empty() ? "" : where + ": ";
  if (known == nullptr) {
    throw InputError(prefix + "unknown unit " + quoted_excerpt(unit) + " (known for " +
                     to_string(quantity) + ": " + units_for(quantity) + ")");
  }
  throw InputError(prefix + "unit " + quoted_excerpt(unit) + " is a " + to_string(known->quantity) +
                   " unit, not one of " + to_string(quantity) + " (" + units_for(quantity) + ")");
}

Sidecar parse_sidecar(const json& json_value, const std::string& file_name) {
  const JsonField root(file_name, "");
  if (!json_value.is_object()) root.fail("expected a JSON object, got " + json_excerpt(json_value));
  Sidecar sidecar;

  if (const json* format = JsonField::find(json_value, "format")) {
    if (!format->is_string() || format->get<std::string>() != kSidecarFormat) {
      (root / "format")
          .fail(std::string("expected \"") + kSidecarFormat + "\", got " + json_excerpt(*format));
    }
  }

  sidecar.sample_rate_hz =
      bounded_number(root.require(json_value, "sample_rate_hz"), kMinSampleRateHz, kMaxSampleRateHz,
                     "Hz", root / "sample_rate_hz");

  if (const json* mass = JsonField::find(json_value, "mass_kg"); mass && !mass->is_null()) {
    sidecar.mass_kg = bounded_number(*mass, kMinMassKg, kMaxMassKg, "kg", root / "mass_kg");
  }

  const json& channels = root.require(json_value, "channels");
  if (!channels.is_array())
    (root / "channels").fail("expected an array, got " + json_excerpt(channels));
  if (channels.empty()) (root / "channels").fail("must list at least one channel");
  std::map<std::string, std::size_t> names;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const JsonField here = (root / "channels")[i];
    ChannelInfo channel = parse_channel(channels[i], here);
    const auto [it, inserted] = names.emplace(channel.name, i);
    if (!inserted) {
      (here / "name")
          .fail("duplicate name " + quoted_excerpt(channel.name) + " (also channels[" +
                std::to_string(it->second) + "])");
    }
    if (channel.ac_coupling_hz && *channel.ac_coupling_hz >= 0.5 * sidecar.sample_rate_hz) {
      (here / "ac_coupling_hz")
          .fail(format_number(*channel.ac_coupling_hz) +
                " Hz is not below the Nyquist frequency, " +
                format_number(0.5 * sidecar.sample_rate_hz) + " Hz");
    }
    sidecar.channels.push_back(std::move(channel));
  }

  if (const json* csv = JsonField::find(json_value, "csv"); csv && !csv->is_null()) {
    sidecar.csv = parse_csv(*csv, root / "csv");
    std::map<int, std::size_t> used;
    for (std::size_t i = 0; i < sidecar.channels.size(); ++i) {
      const int column = sidecar.channels[i].column;
      const JsonField here = (root / "channels")[i] / "column";
      if (column < 0) {
        if (!sidecar.csv->header) here.fail("missing required field (csv.header is false)");
        continue;
      }
      if (column == sidecar.csv->time_column) {
        here.fail(std::to_string(column) + " is csv.time_column");
      }
      const auto [it, inserted] = used.emplace(column, i);
      if (!inserted) {
        here.fail(std::to_string(column) + " is also the column of channels[" +
                  std::to_string(it->second) + "]");
      }
    }
  }

  if (const json* time = JsonField::find(json_value, "time"); time && !time->is_null()) {
    if (sidecar.csv) (root / "time").fail("a CSV file names its time column in csv.time_column");
    sidecar.time = parse_time(*time, root / "time");
  }

  if (const json* excitation = JsonField::find(json_value, "excitation");
      excitation && !excitation->is_null()) {
    sidecar.excitation = parse_excitation(*excitation, root / "excitation");
    const std::optional<double>& frequency = sidecar.excitation->frequency_hz;
    if (frequency && *frequency >= 0.5 * sidecar.sample_rate_hz) {
      (root / "excitation" / "frequency_hz")
          .fail(format_number(*frequency) + " Hz is not below the Nyquist frequency, " +
                format_number(0.5 * sidecar.sample_rate_hz) + " Hz at sample_rate_hz " +
                format_number(sidecar.sample_rate_hz));
    }
  }

  if (const json* notes = JsonField::find(json_value, "notes")) {
    sidecar.notes = (root / "notes").string(*notes);
  }

  if (const json* invalid = JsonField::find(json_value, "invalid_intervals");
      invalid && !invalid->is_null()) {
    sidecar.invalid_intervals = parse_invalid_intervals(*invalid, root / "invalid_intervals");
  }

  for (const auto& [key, item] : json_value.items()) {
    if (key != "format" && key != "sample_rate_hz" && key != "mass_kg" && key != "channels" &&
        key != "csv" && key != "time" && key != "excitation" && key != "notes" &&
        key != "invalid_intervals") {
      sidecar.extra[key] = item;
    }
  }
  return sidecar;
}

json sidecar_to_json(const Sidecar& sidecar) { return json(to_ordered_json(sidecar)); }

std::string sidecar_path_for(const std::string& recording_path) {
  return std::filesystem::path(recording_path).replace_extension(".json").string();
}

Sidecar read_sidecar(const std::string& sidecar_path) {
  return parse_sidecar(read_json_file(sidecar_path, kMaxSidecarBytes), sidecar_path);
}

void write_sidecar(const Sidecar& sidecar, const std::string& sidecar_path) {
  std::string text;
  try {
    const ordered_json out = to_ordered_json(sidecar);
    // Validate what would be written, so that an invalid sidecar never reaches the disk.
    parse_sidecar(json(out), sidecar_path);
    text = out.dump(2) + "\n";
  } catch (const json::exception& error) {
    throw InputError(sidecar_path + ": cannot write the sidecar: " + error.what());
  }
  write_text_file_atomically(text, sidecar_path);
}

}  // namespace oscilab::daq

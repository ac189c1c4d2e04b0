#include "ui/live/live_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/simulation/stepped_levels.h"
#include "daq/recording/json_field.h"
#include "ui/live/live_timeline.h"
#include "ui/number_text.h"

namespace oscilab::ui {
namespace {

using daq::json_excerpt;
using daq::JsonField;

// The number `name` of the object `json` at `field`, if present and not null.
std::optional<double> number_field(const nlohmann::json& json, const char* name,
                                   const JsonField& field) {
  const nlohmann::json* value = JsonField::find(json, name);
  if (value == nullptr || value->is_null()) return std::nullopt;
  return (field / name).number(*value);
}

void require(bool ok, const JsonField& field, double value, const char* why) {
  if (!ok) field.fail(number_text("%g", value) + " (" + why + ")");
}

}  // namespace

std::string to_string(LiveSourceKind kind) {
  switch (kind) {
    case LiveSourceKind::Replay:
      return "replay";
    case LiveSourceKind::Network:
      return "network";
    case LiveSourceKind::Jack:
      return "jack";
    default:
      return "rig";
  }
}

nlohmann::json LiveSettings::to_json() const {
  const auto optional = [](const std::optional<double>& v) -> nlohmann::json {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  return {{"source", to_string(source)},
          {"replay_path", replay_path},
          {"replay_loop", replay_loop},
          {"port", port},
          {"jack",
           {{"server", jack_server},
            {"base_port", jack_base_port},
            {"mass_port", jack_mass_port},
            {"calibration", jack_calibration}}},
          {"rig",
           {{"f0_n", rig_f0_n},
            {"frequency_hz", rig_frequency_hz},
            {"step_n", rig_step_n},
            {"well", analysis::to_string(analysis::well_of(rig_positive_well))}}},
          {"speed", speed},
          {"window_s", window_s},
          {"alarms",
           {{"max_abs_z_m", optional(alarms.max_abs_z_m)},
            {"max_abs_base_m", optional(alarms.max_abs_base_m)},
            {"max_abs_force_n", optional(alarms.max_abs_force_n)}}}};
}

LiveSettings LiveSettings::from_json(const nlohmann::json& json) {
  LiveSettings s;
  if (json.is_null()) return s;
  // The settings are the session's "live" object: messages name their path from there.
  const JsonField root("", "live");
  root.object(json);
  if (json.contains("source")) {
    const nlohmann::json& v = json.at("source");
    const std::string name = v.is_string() ? v.get<std::string>() : v.dump();
    if (name == "rig") {
      s.source = LiveSourceKind::Rig;
    } else if (name == "replay") {
      s.source = LiveSourceKind::Replay;
    } else if (name == "network") {
      s.source = LiveSourceKind::Network;
    } else if (name == "jack") {
      s.source = LiveSourceKind::Jack;
    } else {
      (root / "source").fail("unknown source \"" + name + "\" (rig, replay, network or jack)");
    }
  }
  if (const nlohmann::json* path = JsonField::find(json, "replay_path")) {
    s.replay_path = (root / "replay_path").string(*path);
  }
  if (const nlohmann::json* loop = JsonField::find(json, "replay_loop")) {
    s.replay_loop = (root / "replay_loop").boolean(*loop);
  }
  if (const auto port = number_field(json, "port", root)) {
    require(*port >= 0 && *port <= 65535 && *port == std::floor(*port), root / "port", *port,
            "a TCP port, 0 to 65535");
    s.port = static_cast<int>(*port);
  }
  if (json.contains("jack")) {
    const JsonField at = root / "jack";
    const nlohmann::json& jack = at.object(json.at("jack"));
    const std::pair<const char*, std::string*> fields[] = {{"server", &s.jack_server},
                                                           {"base_port", &s.jack_base_port},
                                                           {"mass_port", &s.jack_mass_port},
                                                           {"calibration", &s.jack_calibration}};
    for (const auto& [name, field] : fields) {
      if (const nlohmann::json* value = JsonField::find(jack, name)) {
        *field = (at / name).string(*value);
      }
    }
  }
  if (json.contains("rig")) {
    const JsonField at = root / "rig";
    const nlohmann::json& rig = at.object(json.at("rig"));
    if (const auto v = number_field(rig, "f0_n", at)) {
      require(*v >= 0, at / "f0_n", *v, "must be >= 0");
      s.rig_f0_n = *v;
    }
    if (const auto v = number_field(rig, "frequency_hz", at)) {
      require(*v > 0, at / "frequency_hz", *v, "must be positive");
      s.rig_frequency_hz = *v;
    }
    if (const auto v = number_field(rig, "step_n", at)) {
      require(*v > 0, at / "step_n", *v, "must be positive");
      s.rig_step_n = *v;
    }
    if (rig.contains("well")) {
      const nlohmann::json& well = rig.at("well");
      const std::optional<analysis::Well> parsed =
          well.is_string() ? analysis::parse_well(well.get<std::string>()) : std::nullopt;
      if (parsed != analysis::Well::Positive && parsed != analysis::Well::Negative) {
        (at / "well").fail("expected \"positive\" or \"negative\", got " + json_excerpt(well));
      }
      s.rig_positive_well = parsed == analysis::Well::Positive;
    }
  }
  if (const auto v = number_field(json, "speed", root)) {
    require(*v >= 0, root / "speed", *v, "must be >= 0; 0: as fast as possible");
    s.speed = *v;
  }
  if (const auto v = number_field(json, "window_s", root)) {
    require(*v >= LiveTimeline::kMinWindowS && *v <= 600.0, root / "window_s", *v, "0.1 to 600 s");
    s.window_s = *v;
  }
  if (json.contains("alarms")) {
    const JsonField at = root / "alarms";
    const nlohmann::json& alarms = at.object(json.at("alarms"));
    const std::pair<const char*, std::optional<double>*> limits[] = {
        {"max_abs_z_m", &s.alarms.max_abs_z_m},
        {"max_abs_base_m", &s.alarms.max_abs_base_m},
        {"max_abs_force_n", &s.alarms.max_abs_force_n}};
    for (const auto& [name, limit] : limits) {
      if (const auto v = number_field(alarms, name, at)) {
        require(*v > 0, at / name, *v, "must be positive, or null: off");
        *limit = *v;
      }
    }
  }
  return s;
}

std::vector<daq::ExcitationStep> stepped_schedule(double from_n, double to_n, double step_n,
                                                  double hold_s, double lead_in_s,
                                                  double frequency_hz) {
  if (!(from_n > 0)) throw InputError("stepped sine: needs a first level above 0 N");
  return daq::rig_schedule(analysis::stepped_levels(from_n, step_n, to_n, "stepped sine"), hold_s,
                           lead_in_s, frequency_hz);
}

}  // namespace oscilab::ui

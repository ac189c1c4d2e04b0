#include "ui/live_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/simulation/stepped_levels.h"
#include "ui/live_timeline.h"
#include "ui/number_text.h"

namespace oscilab::ui {
namespace {

// A double field of `json`, if present: a number, else InputError naming it.
std::optional<double> number_field(const nlohmann::json& json, const char* name,
                                   const std::string& path) {
  if (!json.contains(name) || json.at(name).is_null()) return std::nullopt;
  const nlohmann::json& value = json.at(name);
  if (!value.is_number()) {
    throw InputError(path + "." + name + ": expected a number, got " + value.dump());
  }
  return value.get<double>();
}

void require(bool ok, const std::string& field, double value, const char* why) {
  if (!ok) throw InputError(field + ": " + number_text("%g", value) + " (" + why + ")");
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
            {"well", rig_positive_well ? "positive" : "negative"}}},
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
  if (!json.is_object()) throw InputError("live: expected an object, got " + json.dump());
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
      throw InputError("live.source: unknown source \"" + name +
                       "\" (rig, replay, network or jack)");
    }
  }
  if (json.contains("replay_path")) {
    if (!json.at("replay_path").is_string()) {
      throw InputError("live.replay_path: expected a string, got " + json.at("replay_path").dump());
    }
    s.replay_path = json.at("replay_path").get<std::string>();
  }
  if (json.contains("replay_loop")) {
    if (!json.at("replay_loop").is_boolean()) {
      throw InputError("live.replay_loop: expected true or false, got " +
                       json.at("replay_loop").dump());
    }
    s.replay_loop = json.at("replay_loop").get<bool>();
  }
  if (const auto port = number_field(json, "port", "live")) {
    require(*port >= 0 && *port <= 65535 && *port == std::floor(*port), "live.port", *port,
            "a TCP port, 0 to 65535");
    s.port = static_cast<int>(*port);
  }
  if (json.contains("jack")) {
    const nlohmann::json& jack = json.at("jack");
    if (!jack.is_object()) throw InputError("live.jack: expected an object, got " + jack.dump());
    const std::pair<const char*, std::string*> fields[] = {{"server", &s.jack_server},
                                                           {"base_port", &s.jack_base_port},
                                                           {"mass_port", &s.jack_mass_port},
                                                           {"calibration", &s.jack_calibration}};
    for (const auto& [name, field] : fields) {
      if (!jack.contains(name)) continue;
      if (!jack.at(name).is_string()) {
        throw InputError(std::string("live.jack.") + name + ": expected a string, got " +
                         jack.at(name).dump());
      }
      *field = jack.at(name).get<std::string>();
    }
  }
  if (json.contains("rig")) {
    const nlohmann::json& rig = json.at("rig");
    if (!rig.is_object()) throw InputError("live.rig: expected an object, got " + rig.dump());
    if (const auto v = number_field(rig, "f0_n", "live.rig")) {
      require(*v >= 0, "live.rig.f0_n", *v, "must be >= 0");
      s.rig_f0_n = *v;
    }
    if (const auto v = number_field(rig, "frequency_hz", "live.rig")) {
      require(*v > 0, "live.rig.frequency_hz", *v, "must be positive");
      s.rig_frequency_hz = *v;
    }
    if (const auto v = number_field(rig, "step_n", "live.rig")) {
      require(*v > 0, "live.rig.step_n", *v, "must be positive");
      s.rig_step_n = *v;
    }
    if (rig.contains("well")) {
      const nlohmann::json& well = rig.at("well");
      const std::optional<analysis::Well> parsed =
          well.is_string() ? analysis::parse_well(well.get<std::string>()) : std::nullopt;
      if (parsed != analysis::Well::Positive && parsed != analysis::Well::Negative) {
        throw InputError("live.rig.well: expected \"positive\" or \"negative\", got " +
                         well.dump());
      }
      s.rig_positive_well = parsed == analysis::Well::Positive;
    }
  }
  if (const auto v = number_field(json, "speed", "live")) {
    require(*v >= 0, "live.speed", *v, "must be >= 0; 0: as fast as possible");
    s.speed = *v;
  }
  if (const auto v = number_field(json, "window_s", "live")) {
    require(*v >= LiveTimeline::kMinWindowS && *v <= 600.0, "live.window_s", *v, "0.1 to 600 s");
    s.window_s = *v;
  }
  if (json.contains("alarms")) {
    const nlohmann::json& alarms = json.at("alarms");
    if (!alarms.is_object()) {
      throw InputError("live.alarms: expected an object, got " + alarms.dump());
    }
    const std::pair<const char*, std::optional<double>*> limits[] = {
        {"max_abs_z_m", &s.alarms.max_abs_z_m},
        {"max_abs_base_m", &s.alarms.max_abs_base_m},
        {"max_abs_force_n", &s.alarms.max_abs_force_n}};
    for (const auto& [name, limit] : limits) {
      if (const auto v = number_field(alarms, name, "live.alarms")) {
        require(*v > 0, std::string("live.alarms.") + name, *v, "must be positive, or null: off");
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

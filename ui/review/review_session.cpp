#include "ui/review/review_session.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <utility>

#include "analysis/common/input_error.h"
#include "daq/recording/json_field.h"
#include "daq/recording/json_file.h"

namespace oscilab::ui {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using daq::json_excerpt;
using daq::JsonField;

// An index into the session's recordings.
int recording_index(const JsonField& field, const json& value, std::size_t recordings) {
  const long index = field.integer(value, 0);
  if (std::size_t(index) >= recordings) {
    field.fail(json_excerpt(value) + " is not an index into recordings (" +
               std::to_string(recordings) + (recordings == 1 ? " recording)" : " recordings)"));
  }
  return int(index);
}

// `path` relative to `dir` when both are absolute on one root, else as it is.
std::string relative_path(const std::string& path, const std::string& dir) {
  const fs::path p = fs::path(path).lexically_normal();
  if (!p.is_absolute() || dir.empty()) return p.generic_string();
  const fs::path relative = p.lexically_relative(fs::path(dir).lexically_normal());
  return relative.empty() ? p.generic_string() : relative.generic_string();
}

std::string resolve_path(const std::string& path, const std::string& dir) {
  const fs::path p(path);
  if (p.is_absolute() || dir.empty()) return p.lexically_normal().string();
  return (fs::path(dir) / p).lexically_normal().string();
}

// Index of `path` in `recordings`, or -1.
int index_of(const std::vector<std::string>& recordings, const std::string& path) {
  for (std::size_t i = 0; i < recordings.size(); ++i) {
    if (recordings[i] == path) return int(i);
  }
  return -1;
}

}  // namespace

analysis::PipelineSettings pipeline_settings_from_json(const json& value,
                                                       const std::string& file_name,
                                                       const std::string& field) {
  const JsonField at(file_name, field);
  at.object(value);
  analysis::PipelineSettings settings;
  // Integers ≥ 1; reals > 0 unless said otherwise. The names are PipelineSettings::to_json's.
  const std::map<std::string, int analysis::PipelineSettings::*> integers = {
      {"harmonics", &analysis::PipelineSettings::harmonics},
      {"min_steady_cycles", &analysis::PipelineSettings::min_steady_cycles},
      {"stiffness_bins", &analysis::PipelineSettings::stiffness_bins},
      {"damping_bins", &analysis::PipelineSettings::damping_bins}};
  const std::map<std::string, double analysis::PipelineSettings::*> positives = {
      {"steady_rel_tol", &analysis::PipelineSettings::steady_rel_tol},
      {"level_change_rel", &analysis::PipelineSettings::level_change_rel},
      {"integration_highpass_hz", &analysis::PipelineSettings::integration_highpass_hz},
      {"derivative_lowpass_hz", &analysis::PipelineSettings::derivative_lowpass_hz},
      {"stiffness_velocity_band_rel", &analysis::PipelineSettings::stiffness_velocity_band_rel},
      {"damping_position_band_rel", &analysis::PipelineSettings::damping_position_band_rel}};
  for (const auto& [key, member] : value.items()) {
    const JsonField here = at / key;
    if (const auto i = integers.find(key); i != integers.end()) {
      settings.*(i->second) = int(here.integer(member, 1));
    } else if (const auto d = positives.find(key); d != positives.end()) {
      const double x = here.finite_number(member);
      if (!(x > 0.0)) here.fail("expected a positive number, got " + json_excerpt(member));
      settings.*(d->second) = x;
    } else if (key == "well_boundary_m") {
      settings.well_boundary_m = here.finite_number(member);
    } else if (key == "edge_trim_s") {
      const double x = here.finite_number(member);
      if (x < 0.0) here.fail("expected a number \u2265 0, got " + json_excerpt(member));
      settings.edge_trim_s = x;
    } else {
      here.fail("unknown setting");
    }
  }
  return settings;
}

json session_to_json(const Session& session, const std::string& session_dir) {
  json out = json::object();
  out["format"] = kSessionFormat;
  json recordings = json::array();
  for (const std::string& path : session.recordings) {
    recordings.push_back(relative_path(path, session_dir));
  }
  out["recordings"] = recordings;
  out["analysis"] = session.settings.to_json();
  out["layout"] = {{"geometry", session.window_geometry_base64},
                   {"state", session.window_state_base64}};
  json view = json::object();
  if (const int shown = index_of(session.recordings, session.shown_recording); shown >= 0) {
    view["recording"] = shown;
  }
  if (session.time_window) {
    view["time_window_s"] = {session.time_window->start_s, session.time_window->end_s};
  }
  if (session.cursor_s) view["cursor_s"] = *session.cursor_s;
  out["view"] = view;
  json levels = json::array();
  for (const Session::LevelRef& level : session.selected_levels) {
    const int recording = index_of(session.recordings, level.recording);
    if (recording >= 0) levels.push_back({{"recording", recording}, {"level", level.level}});
  }
  out["selected_levels"] = levels;
  json annotations = json::array();
  for (const Annotation& annotation : session.annotations) {
    const int recording = index_of(session.recordings, annotation.recording);
    if (recording < 0) continue;
    annotations.push_back(
        {{"recording", recording}, {"t_s", annotation.t_s}, {"text", annotation.text}});
  }
  out["annotations"] = annotations;
  out["live"] = session.live;
  return out;
}

Session session_from_json(const json& value, const std::string& session_dir,
                          const std::string& file_name) {
  const JsonField root(file_name, "");
  root.object(value);
  root.only(value, {"format", "recordings", "analysis", "layout", "view", "selected_levels",
                    "annotations", "live"});
  const json* format = JsonField::find(value, "format");
  if (!format) (root / "format").fail("missing (expected \"" + std::string(kSessionFormat) + "\")");
  if (!format->is_string() || format->get<std::string>() != kSessionFormat) {
    (root / "format")
        .fail("expected \"" + std::string(kSessionFormat) + "\", got " + json_excerpt(*format));
  }

  Session session;
  if (const json* recordings = JsonField::find(value, "recordings")) {
    const JsonField at = root / "recordings";
    at.array(*recordings);
    for (std::size_t i = 0; i < recordings->size(); ++i) {
      const std::string path = at[i].string((*recordings)[i]);
      if (path.empty()) at[i].fail("empty path");
      session.recordings.push_back(resolve_path(path, session_dir));
    }
  }
  const std::size_t count = session.recordings.size();
  if (const json* analysis = JsonField::find(value, "analysis")) {
    session.settings = pipeline_settings_from_json(*analysis, file_name, "analysis");
  }
  if (const json* layout = JsonField::find(value, "layout")) {
    const JsonField at = root / "layout";
    at.object(*layout);
    at.only(*layout, {"geometry", "state"});
    if (const json* g = JsonField::find(*layout, "geometry")) {
      session.window_geometry_base64 = (at / "geometry").string(*g);
    }
    if (const json* s = JsonField::find(*layout, "state")) {
      session.window_state_base64 = (at / "state").string(*s);
    }
  }
  if (const json* view = JsonField::find(value, "view")) {
    const JsonField at = root / "view";
    at.object(*view);
    at.only(*view, {"recording", "time_window_s", "cursor_s"});
    if (const json* shown = JsonField::find(*view, "recording")) {
      session.shown_recording =
          session.recordings[std::size_t(recording_index(at / "recording", *shown, count))];
    }
    if (const json* window = JsonField::find(*view, "time_window_s")) {
      const JsonField w = at / "time_window_s";
      w.array(*window);
      if (window->size() != 2) w.fail("expected [start_s, end_s], got " + json_excerpt(*window));
      const TimeWindow span{w[0].finite_number((*window)[0]), w[1].finite_number((*window)[1])};
      if (!(span.end_s > span.start_s)) w.fail("end before start: " + json_excerpt(*window));
      session.time_window = span;
    }
    if (const json* cursor = JsonField::find(*view, "cursor_s")) {
      session.cursor_s = (at / "cursor_s").finite_number(*cursor);
    }
  }
  if (const json* levels = JsonField::find(value, "selected_levels")) {
    const JsonField at = root / "selected_levels";
    at.array(*levels);
    for (std::size_t i = 0; i < levels->size(); ++i) {
      const json& level = at[i].object((*levels)[i]);
      at[i].only(level, {"recording", "level"});
      const json* recording = JsonField::find(level, "recording");
      const json* index = JsonField::find(level, "level");
      if (!recording) (at[i] / "recording").fail("missing");
      if (!index) (at[i] / "level").fail("missing");
      session.selected_levels.push_back(
          {session.recordings[std::size_t(recording_index(at[i] / "recording", *recording, count))],
           int((at[i] / "level").integer(*index, 0))});
    }
  }
  if (const json* annotations = JsonField::find(value, "annotations")) {
    const JsonField at = root / "annotations";
    at.array(*annotations);
    for (std::size_t i = 0; i < annotations->size(); ++i) {
      const json& entry = at[i].object((*annotations)[i]);
      at[i].only(entry, {"recording", "t_s", "text"});
      Annotation annotation;
      for (const char* key : {"recording", "t_s", "text"}) {
        if (!JsonField::find(entry, key)) (at[i] / key).fail("missing");
      }
      annotation.recording = session.recordings[std::size_t(
          recording_index(at[i] / "recording", entry.at("recording"), count))];
      annotation.t_s = (at[i] / "t_s").finite_number(entry.at("t_s"));
      annotation.text = (at[i] / "text").string(entry.at("text"));
      session.annotations.push_back(std::move(annotation));
    }
  }
  if (const json* live = JsonField::find(value, "live"))
    session.live = (root / "live").object(*live);
  return session;
}

void write_session(const Session& session, const std::string& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  const std::string dir = error ? std::string() : absolute.parent_path().string();
  const std::string text = session_to_json(session, dir).dump(2) + "\n";
  daq::write_text_file_atomically(text, path);  // a failed write keeps the old file
}

Session read_session(const std::string& path) {
  constexpr std::uintmax_t kMaxSessionBytes = 64u << 20;  // a session is kilobytes
  const json value = daq::read_json_file(path, kMaxSessionBytes);
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  return session_from_json(value, error ? std::string() : absolute.parent_path().string(), path);
}

}  // namespace oscilab::ui

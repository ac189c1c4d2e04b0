#include "ui/review_session.h"

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
#include "daq/recording/json_file.h"

namespace oscilab::ui {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A JSON value as it appears in a message, shortened so that a huge value cannot flood it.
std::string show(const json& value) {
  std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  constexpr std::size_t kMaxShown = 60;  // characters
  if (text.size() > kMaxShown) text = text.substr(0, kMaxShown) + "...";
  return text;
}

// Where a value sits: the file and the JSON path inside it, "review.json: annotations[1].t_s".
class Field {
 public:
  Field(std::string file, std::string path) : file_(std::move(file)), path_(std::move(path)) {}

  Field operator/(const std::string& key) const {
    return Field(file_, path_.empty() ? key : path_ + "." + key);
  }
  Field operator[](std::size_t index) const {
    return Field(file_, path_ + "[" + std::to_string(index) + "]");
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_ + ": " + (path_.empty() ? "" : path_ + ": ") + problem);
  }

  const json& object(const json& value) const {
    if (!value.is_object()) fail("expected an object, got " + show(value));
    return value;
  }
  const json& array(const json& value) const {
    if (!value.is_array()) fail("expected an array, got " + show(value));
    return value;
  }
  std::string string(const json& value) const {
    if (!value.is_string()) fail("expected a string, got " + show(value));
    return value.get<std::string>();
  }
  double number(const json& value) const {
    if (!value.is_number()) fail("expected a number, got " + show(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail("expected a finite number, got " + show(value));
    return x;
  }
  long integer(const json& value, long min) const {
    if (!value.is_number_integer()) fail("expected an integer, got " + show(value));
    const long x = value.get<long>();
    if (x < min) fail("expected an integer \u2265 " + std::to_string(min) + ", got " + show(value));
    return x;
  }
  // An index into the session's recordings.
  int recording_index(const json& value, std::size_t recordings) const {
    const long index = integer(value, 0);
    if (std::size_t(index) >= recordings) {
      fail(show(value) + " is not an index into recordings (" + std::to_string(recordings) +
           (recordings == 1 ? " recording)" : " recordings)"));
    }
    return int(index);
  }
  // Fails on a member of `value` that is not in `known`.
  void only(const json& value, std::initializer_list<const char*> known) const {
    for (const auto& [key, member] : value.items()) {
      bool found = false;
      for (const char* name : known) found = found || key == name;
      if (!found) (*this / key).fail("unknown member");
    }
  }

 private:
  std::string file_;
  std::string path_;
};

const json* find(const json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
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
  const Field at(file_name, field);
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
    const Field here = at / key;
    if (const auto i = integers.find(key); i != integers.end()) {
      settings.*(i->second) = int(here.integer(member, 1));
    } else if (const auto d = positives.find(key); d != positives.end()) {
      const double x = here.number(member);
      if (!(x > 0.0)) here.fail("expected a positive number, got " + show(member));
      settings.*(d->second) = x;
    } else if (key == "well_boundary_m") {
      settings.well_boundary_m = here.number(member);
    } else if (key == "edge_trim_s") {
      const double x = here.number(member);
      if (x < 0.0) here.fail("expected a number \u2265 0, got " + show(member));
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
  const Field root(file_name, "");
  root.object(value);
  root.only(value, {"format", "recordings", "analysis", "layout", "view", "selected_levels",
                    "annotations", "live"});
  const json* format = find(value, "format");
  if (!format) (root / "format").fail("missing (expected \"" + std::string(kSessionFormat) + "\")");
  if (!format->is_string() || format->get<std::string>() != kSessionFormat) {
    (root / "format")
        .fail("expected \"" + std::string(kSessionFormat) + "\", got " + show(*format));
  }

  Session session;
  if (const json* recordings = find(value, "recordings")) {
    const Field at = root / "recordings";
    at.array(*recordings);
    for (std::size_t i = 0; i < recordings->size(); ++i) {
      const std::string path = at[i].string((*recordings)[i]);
      if (path.empty()) at[i].fail("empty path");
      session.recordings.push_back(resolve_path(path, session_dir));
    }
  }
  const std::size_t count = session.recordings.size();
  if (const json* analysis = find(value, "analysis")) {
    session.settings = pipeline_settings_from_json(*analysis, file_name, "analysis");
  }
  if (const json* layout = find(value, "layout")) {
    const Field at = root / "layout";
    at.object(*layout);
    at.only(*layout, {"geometry", "state"});
    if (const json* g = find(*layout, "geometry")) {
      session.window_geometry_base64 = (at / "geometry").string(*g);
    }
    if (const json* s = find(*layout, "state")) {
      session.window_state_base64 = (at / "state").string(*s);
    }
  }
  if (const json* view = find(value, "view")) {
    const Field at = root / "view";
    at.object(*view);
    at.only(*view, {"recording", "time_window_s", "cursor_s"});
    if (const json* shown = find(*view, "recording")) {
      session.shown_recording =
          session.recordings[std::size_t((at / "recording").recording_index(*shown, count))];
    }
    if (const json* window = find(*view, "time_window_s")) {
      const Field w = at / "time_window_s";
      w.array(*window);
      if (window->size() != 2) w.fail("expected [start_s, end_s], got " + show(*window));
      const TimeWindow span{w[0].number((*window)[0]), w[1].number((*window)[1])};
      if (!(span.end_s > span.start_s)) w.fail("end before start: " + show(*window));
      session.time_window = span;
    }
    if (const json* cursor = find(*view, "cursor_s")) {
      session.cursor_s = (at / "cursor_s").number(*cursor);
    }
  }
  if (const json* levels = find(value, "selected_levels")) {
    const Field at = root / "selected_levels";
    at.array(*levels);
    for (std::size_t i = 0; i < levels->size(); ++i) {
      const json& level = at[i].object((*levels)[i]);
      at[i].only(level, {"recording", "level"});
      const json* recording = find(level, "recording");
      const json* index = find(level, "level");
      if (!recording) (at[i] / "recording").fail("missing");
      if (!index) (at[i] / "level").fail("missing");
      session.selected_levels.push_back(
          {session
               .recordings[std::size_t((at[i] / "recording").recording_index(*recording, count))],
           int((at[i] / "level").integer(*index, 0))});
    }
  }
  if (const json* annotations = find(value, "annotations")) {
    const Field at = root / "annotations";
    at.array(*annotations);
    for (std::size_t i = 0; i < annotations->size(); ++i) {
      const json& entry = at[i].object((*annotations)[i]);
      at[i].only(entry, {"recording", "t_s", "text"});
      Annotation annotation;
      for (const char* key : {"recording", "t_s", "text"}) {
        if (!find(entry, key)) (at[i] / key).fail("missing");
      }
      annotation.recording = session.recordings[std::size_t(
          (at[i] / "recording").recording_index(entry.at("recording"), count))];
      annotation.t_s = (at[i] / "t_s").number(entry.at("t_s"));
      annotation.text = (at[i] / "text").string(entry.at("text"));
      session.annotations.push_back(std::move(annotation));
    }
  }
  if (const json* live = find(value, "live")) session.live = (root / "live").object(*live);
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

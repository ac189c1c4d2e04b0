#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/pipeline/pipeline_settings.h"
#include "ui/plots/annotation.h"
#include "ui/time_window.h"

namespace oscilab::ui {

/// The format tag of a session file.
inline constexpr const char* kSessionFormat = "oscilab-session/1";

/// A saved record review (File ▸ Save session…): what was opened, how it was analysed, what was
/// shown and noted. Qt-free; the main window fills and applies it.
///
/// In memory every recording is an absolute path, and levels and annotations name their
/// recording by that path. In the file (session_to_json) recordings are written relative to the
/// session file's folder and the others refer to them by index:
///
///     {
///       "format": "oscilab-session/1",
///       "recordings": ["stepped_positive.flac", "../other/stepped_negative.flac"],
///       "analysis": {"harmonics": 8, ...},          // PipelineSettings::to_json
///       "layout": {"geometry": "AdnQyw...", "state": "AAAA/w..."},  // Qt's, base64
///       "view": {"recording": 0, "time_window_s": [80.0, 95.0], "cursor_s": 87.5},
///       "selected_levels": [{"recording": 0, "level": 11}],   // the first is the current one
///       "annotations": [{"recording": 0, "t_s": 87.5, "text": "rattle"}],
///       "live": {}                                    // the live monitor's, kept verbatim
///     }
///
/// Every member but "format" may be left out (its default is used).
struct Session {
  struct LevelRef {
    std::string recording;  // absolute path
    int level = 0;          // index into that recording's levels (analysis order)
    bool operator==(const LevelRef&) const = default;
  };

  std::vector<std::string> recordings;  // absolute paths, in the order they were opened
  analysis::PipelineSettings settings;
  std::string window_geometry_base64;  // QMainWindow::saveGeometry
  std::string window_state_base64;     // QMainWindow::saveState
  std::string shown_recording;         // absolute path; empty: none
  std::optional<TimeWindow> time_window;
  std::optional<double> cursor_s;
  std::vector<LevelRef> selected_levels;
  std::vector<Annotation> annotations;
  nlohmann::json live = nlohmann::json::object();
};

/// The session as the file holds it; paths relative to `session_dir` where a relative path
/// exists (always on one file system root), otherwise absolute. Levels and annotations whose
/// recording is not among `session.recordings` are left out.
nlohmann::json session_to_json(const Session& session, const std::string& session_dir);

/// Reads a session from its JSON. Relative paths are resolved against `session_dir`. Throws
/// InputError naming `file_name`, the field and the value, e.g.
/// `review.json: annotations[1].t_s: expected a number, got "soon"`.
Session session_from_json(const nlohmann::json& json, const std::string& session_dir,
                          const std::string& file_name);

/// PipelineSettings from the JSON of PipelineSettings::to_json; members left out keep their
/// defaults, an unknown member or a value of the wrong type or range throws InputError naming
/// `file_name` and `field` (e.g. "analysis").
analysis::PipelineSettings pipeline_settings_from_json(const nlohmann::json& json,
                                                       const std::string& file_name,
                                                       const std::string& field);

/// Writes `session` to `path` (JSON, two-space indent). Throws InputError when it cannot.
void write_session(const Session& session, const std::string& path);
/// Reads the session file at `path`. Throws InputError naming the file (and the field).
Session read_session(const std::string& path);

}  // namespace oscilab::ui

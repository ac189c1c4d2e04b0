// Session files of the record review: round trip, paths relative to the session file,
// and one error naming the file and field for each kind of bad content.
#include "ui/review/review_session.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

namespace oscilab::ui {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Session full_session() {
  Session session;
  session.recordings = {"/lab/sessions/run1.flac", "/lab/recordings/run2.flac"};
  session.settings.harmonics = 6;
  session.settings.derivative_lowpass_hz = 45.0;
  session.settings.edge_trim_s = 0.5;
  session.window_geometry_base64 = "AdnQywADAAA=";
  session.window_state_base64 = "AAAA/wAAAAD9";
  session.shown_recording = "/lab/recordings/run2.flac";
  session.time_window = TimeWindow{80.0, 95.5};
  session.cursor_s = 87.25;
  session.selected_levels = {{"/lab/recordings/run2.flac", 11}, {"/lab/sessions/run1.flac", 3}};
  session.annotations = {{"/lab/sessions/run1.flac", 12.5, "rattle"},
                         {"/lab/recordings/run2.flac", 100.0, "jump to z\u208b*"}};
  session.live = {{"host", "rig-2"}, {"port", 5025}, {"plots", {1, 2, 3}}};
  return session;
}

void expect_same(const Session& a, const Session& b) {
  EXPECT_EQ(a.recordings, b.recordings);
  EXPECT_EQ(a.settings.to_json(), b.settings.to_json());
  EXPECT_EQ(a.window_geometry_base64, b.window_geometry_base64);
  EXPECT_EQ(a.window_state_base64, b.window_state_base64);
  EXPECT_EQ(a.shown_recording, b.shown_recording);
  ASSERT_EQ(a.time_window.has_value(), b.time_window.has_value());
  if (a.time_window) {
    EXPECT_EQ(a.time_window->start_s, b.time_window->start_s);
    EXPECT_EQ(a.time_window->end_s, b.time_window->end_s);
  }
  EXPECT_EQ(a.cursor_s, b.cursor_s);
  EXPECT_EQ(a.selected_levels, b.selected_levels);
  EXPECT_EQ(a.annotations, b.annotations);
  EXPECT_EQ(a.live, b.live);
}

TEST(Session, RoundTripsThroughJson) {
  const Session session = full_session();
  const json saved = session_to_json(session, "/lab/sessions");
  EXPECT_EQ(saved.at("format"), "oscilab-session/1");
  expect_same(session_from_json(saved, "/lab/sessions", "s.json"), session);
  // Through text too: doubles print to the shortest text that reads back exactly.
  expect_same(session_from_json(json::parse(saved.dump(2)), "/lab/sessions", "s.json"), session);
}

TEST(Session, WritesRecordingsRelativeToTheSessionFolderAndResolvesThemBack) {
  const json saved = session_to_json(full_session(), "/lab/sessions");
  EXPECT_EQ(saved.at("recordings"), json({"run1.flac", "../recordings/run2.flac"}));
  // Levels, annotations and the shown recording refer to recordings by index.
  EXPECT_EQ(saved.at("view").at("recording"), 1);
  EXPECT_EQ(saved.at("selected_levels")[0], json({{"recording", 1}, {"level", 11}}));
  EXPECT_EQ(saved.at("annotations")[0].at("recording"), 0);
  // The session moved with its recordings: they are found beside it.
  const Session moved = session_from_json(saved, "/elsewhere/sessions", "s.json");
  EXPECT_EQ(moved.recordings, (std::vector<std::string>{"/elsewhere/sessions/run1.flac",
                                                        "/elsewhere/recordings/run2.flac"}));
  EXPECT_EQ(moved.annotations[1].recording, "/elsewhere/recordings/run2.flac");
  // Absolute paths in a file are kept as they are.
  json edited = saved;
  edited["recordings"][0] = "/data/run9.flac";
  EXPECT_EQ(session_from_json(edited, "/lab/sessions", "s.json").recordings[0], "/data/run9.flac");
}

TEST(Session, MembersLeftOutTakeTheirDefaults) {
  const Session session =
      session_from_json(json{{"format", "oscilab-session/1"}}, "/lab", "s.json");
  EXPECT_TRUE(session.recordings.empty());
  EXPECT_EQ(session.settings.to_json(), analysis::PipelineSettings{}.to_json());
  EXPECT_FALSE(session.time_window.has_value());
  EXPECT_EQ(session.live, json::object());
}

TEST(Session, PipelineSettingsRoundTripEveryField) {
  analysis::PipelineSettings settings;
  settings.harmonics = 5;
  settings.well_boundary_m = -1e-3;
  settings.min_steady_cycles = 7;
  settings.steady_rel_tol = 3e-4;
  settings.level_change_rel = 0.05;
  settings.integration_highpass_hz = 0.5;
  settings.derivative_lowpass_hz = 40.0;
  settings.stiffness_velocity_band_rel = 0.03;
  settings.stiffness_bins = 50;
  settings.damping_position_band_rel = 0.02;
  settings.damping_bins = 30;
  settings.edge_trim_s = 2.0;
  // Every member of to_json is read back (a member the reader did not know would throw).
  EXPECT_EQ(pipeline_settings_from_json(settings.to_json(), "s.json", "analysis").to_json(),
            settings.to_json());
}

// Each bad value gives one message naming the file, the field and the value.
TEST(Session, ThrowsInputErrorNamingFileAndField) {
  const json good = session_to_json(full_session(), "/lab/sessions");
  const auto error_of = [](const json& value) -> std::string {
    try {
      session_from_json(value, "/lab/sessions", "review.json");
    } catch (const InputError& error) {
      return error.what();
    }
    return "no error";
  };
  const auto with = [&](const json::json_pointer& pointer, const json& value) {
    json edited = good;
    edited[pointer] = value;
    return error_of(edited);
  };
  EXPECT_EQ(error_of(json::array()), "review.json: expected an object, got []");
  EXPECT_EQ(with("/format"_json_pointer, "oscilab-session/2"),
            "review.json: format: expected \"oscilab-session/1\", got \"oscilab-session/2\"");
  json no_format = good;
  no_format.erase("format");
  EXPECT_EQ(error_of(no_format), "review.json: format: missing (expected \"oscilab-session/1\")");
  EXPECT_EQ(with("/recordings/1"_json_pointer, 7),
            "review.json: recordings[1]: expected a string, got 7");
  EXPECT_EQ(with("/annotations/1/t_s"_json_pointer, "soon"),
            "review.json: annotations[1].t_s: expected a number, got \"soon\"");
  EXPECT_EQ(with("/annotations/0/recording"_json_pointer, 2),
            "review.json: annotations[0].recording: 2 is not an index into recordings "
            "(2 recordings)");
  EXPECT_EQ(with("/selected_levels/0/level"_json_pointer, -1),
            "review.json: selected_levels[0].level: expected an integer \u2265 0, got -1");
  EXPECT_EQ(with("/analysis/harmonics"_json_pointer, 0),
            "review.json: analysis.harmonics: expected an integer \u2265 1, got 0");
  EXPECT_EQ(with("/analysis/derivative_lowpass_hz"_json_pointer, -60.0),
            "review.json: analysis.derivative_lowpass_hz: expected a positive number, got -60.0");
  EXPECT_EQ(with("/analysis/harmonix"_json_pointer, 8),
            "review.json: analysis.harmonix: unknown setting");
  EXPECT_EQ(with("/view/time_window_s"_json_pointer, json({95.0, 80.0})),
            "review.json: view.time_window_s: end before start: [95.0,80.0]");
  EXPECT_EQ(with("/view/zoom"_json_pointer, 2), "review.json: view.zoom: unknown member");
  EXPECT_EQ(with("/layout/state"_json_pointer, 42),
            "review.json: layout.state: expected a string, got 42");
  EXPECT_EQ(with("/live"_json_pointer, 3), "review.json: live: expected an object, got 3");
  EXPECT_EQ(with("/selected_levels/0"_json_pointer, json{{"recording", 0}}),
            "review.json: selected_levels[0].level: missing");
}

TEST(Session, FileRoundTripAndFileErrors) {
  const fs::path dir = fs::temp_directory_path() / "oscilab_review_session_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "recordings");
  Session session = full_session();
  session.recordings = {(dir / "recordings" / "a.flac").string(), "/lab/b.flac"};
  session.shown_recording = session.recordings[0];
  session.selected_levels = {{session.recordings[0], 2}};
  session.annotations = {{session.recordings[1], 1.5, "note"}};
  const std::string path = (dir / "review.json").string();
  write_session(session, path);
  std::ifstream in(path);
  const json written = json::parse(in);
  EXPECT_EQ(written.at("recordings")[0], "recordings/a.flac");
  expect_same(read_session(path), session);

  std::ofstream(dir / "broken.json") << "{\"format\": \"oscilab-session/1\",";
  try {
    read_session((dir / "broken.json").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(
        std::string(error.what()).rfind((dir / "broken.json").string() + ": malformed JSON: ", 0),
        0u)
        << error.what();
  }
  EXPECT_THROW(
      {
        try {
          read_session((dir / "missing.json").string());
        } catch (const InputError& error) {
          EXPECT_EQ(std::string(error.what()),
                    (dir / "missing.json").string() + ": file not found");
          throw;
        }
      },
      InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace oscilab::ui

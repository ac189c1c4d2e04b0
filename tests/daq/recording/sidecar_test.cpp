#include "daq/recording/sidecar.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using nlohmann::json;
using testing::input_error_of;

// A complete sidecar in the format of docs/contracts.md §1: format, rate, mass, two channels, a
// stepped-sine excitation with one level, notes.
json contract_example() {
  return json::parse(R"({
    "format": "oscilab-recording/1",
    "sample_rate_hz": 512,
    "mass_kg": 0.26,
    "channels": [
      {"name": "base_acc", "role": "base", "quantity": "acceleration", "unit": "m/s^2",
       "scale": 1.0, "offset": 0.0, "sensor": "accelerometer"},
      {"name": "y", "role": "mass", "quantity": "displacement", "unit": "m",
       "scale": 1.0, "offset": 0.0, "sensor": "laser vibrometer"}
    ],
    "excitation": {"type": "stepped-sine", "frequency_hz": 9.0,
                   "levels": [{"f0_n": 0.2, "start_s": 0.0, "end_s": 10.0}]},
    "notes": "free text"
  })");
}

std::string parse_error_of(const json& value) {
  return input_error_of([&] { parse_sidecar(value, "run1.json"); });
}

TEST(SidecarReader, ReadsEveryFieldOfTheContractExample) {
  const Sidecar sidecar = parse_sidecar(contract_example(), "run1.json");
  EXPECT_EQ(sidecar.sample_rate_hz, 512.0);
  ASSERT_TRUE(sidecar.mass_kg.has_value());
  EXPECT_EQ(*sidecar.mass_kg, 0.26);
  ASSERT_EQ(sidecar.channels.size(), 2u);
  EXPECT_EQ(sidecar.channels[0].name, "base_acc");
  EXPECT_EQ(sidecar.channels[0].role, ChannelRole::Base);
  EXPECT_EQ(sidecar.channels[0].quantity, Quantity::Acceleration);
  EXPECT_EQ(sidecar.channels[0].unit, "m/s^2");
  EXPECT_EQ(sidecar.channels[0].sensor, "accelerometer");
  EXPECT_EQ(sidecar.channels[1].role, ChannelRole::Mass);
  EXPECT_EQ(sidecar.channels[1].quantity, Quantity::Displacement);
  EXPECT_EQ(sidecar.channels[1].column, -1);
  ASSERT_TRUE(sidecar.excitation.has_value());
  EXPECT_EQ(sidecar.excitation->type, "stepped-sine");
  ASSERT_TRUE(sidecar.excitation->frequency_hz.has_value());
  EXPECT_EQ(*sidecar.excitation->frequency_hz, 9.0);
  ASSERT_EQ(sidecar.excitation->levels.size(), 1u);
  EXPECT_EQ(sidecar.excitation->levels[0].f0_n, 0.2);
  EXPECT_EQ(sidecar.excitation->levels[0].end_s, 10.0);
  EXPECT_EQ(sidecar.notes, "free text");
  EXPECT_FALSE(sidecar.csv.has_value());
  EXPECT_TRUE(sidecar.extra.empty());
}

TEST(SidecarReader, RoundTripKeepsUnknownKeysAtEveryLevel) {
  json value = contract_example();
  value["operator"] = "A. N. Other";
  value["channels"][0]["serial"] = 4711;
  value["excitation"]["amplifier_gain"] = 3;
  value["excitation"]["levels"][0]["comment"] = "settled";
  value["csv"] = {{"header", false}, {"delimiter", ";"}, {"skip_lines", 2}, {"time_column", 0}};
  value["channels"][0]["column"] = 1;
  value["channels"][1]["column"] = 3;

  const Sidecar sidecar = parse_sidecar(value, "run1.json");
  EXPECT_EQ(sidecar.extra.at("operator"), "A. N. Other");
  EXPECT_EQ(sidecar.channels[0].extra.at("serial"), 4711);
  EXPECT_EQ(sidecar.excitation->extra.at("amplifier_gain"), 3);
  EXPECT_EQ(sidecar.excitation->levels[0].extra.at("comment"), "settled");
  ASSERT_TRUE(sidecar.csv.has_value());
  EXPECT_FALSE(sidecar.csv->header);
  EXPECT_EQ(sidecar.csv->delimiter, ';');
  EXPECT_EQ(sidecar.csv->skip_lines, 2);
  EXPECT_EQ(sidecar.csv->time_column, 0);

  // Written back, the JSON is the input (scale and offset are always written out).
  EXPECT_EQ(sidecar_to_json(sidecar), value);
  EXPECT_EQ(sidecar_to_json(parse_sidecar(sidecar_to_json(sidecar), "run1.json")), value);
}

TEST(SidecarReader, KeepsTheSoundCardKeysOfAChannel) {
  // ac_coupling_hz and full_scale_v (docs/contracts.md §1) are read and written back.
  json value = contract_example();
  value["channels"][1]["ac_coupling_hz"] = 2.2;
  value["channels"][1]["full_scale_v"] = 7.75;
  const Sidecar sidecar = parse_sidecar(value, "run1.json");
  EXPECT_EQ(sidecar.channels[1].ac_coupling_hz, 2.2);
  EXPECT_EQ(sidecar.channels[1].full_scale_v, 7.75);
  EXPECT_FALSE(sidecar.channels[0].ac_coupling_hz);
  EXPECT_TRUE(sidecar.channels[1].extra.empty());
  const json back = sidecar_to_json(sidecar);
  EXPECT_EQ(back["channels"][1]["ac_coupling_hz"], 2.2);
  EXPECT_EQ(back["channels"][1]["full_scale_v"], 7.75);
  EXPECT_FALSE(back["channels"][0].contains("ac_coupling_hz"));
}

TEST(SidecarReader, ThrowsInputErrorWhenRateIsMissing) {
  json value = contract_example();
  value.erase("sample_rate_hz");
  EXPECT_EQ(parse_error_of(value), "run1.json: sample_rate_hz: missing required field");
}

TEST(SidecarReader, ThrowsInputErrorNamingFileFieldAndValueWhenUnitIsUnknown) {
  json value = contract_example();
  value["channels"][1]["unit"] = "mps";
  const std::string message = parse_error_of(value);
  EXPECT_EQ(message.rfind("run1.json: channels[1].unit: unknown unit \"mps\"", 0), 0u) << message;
}

TEST(SidecarReader, ThrowsInputErrorWhenUnitDoesNotFitQuantity) {
  json value = contract_example();
  value["channels"][0]["unit"] = "mm";
  EXPECT_EQ(parse_error_of(value).rfind("run1.json: channels[0].unit: unit \"mm\" is a "
                                        "displacement unit, not one of acceleration",
                                        0),
            0u)
      << parse_error_of(value);
}

// Each invalid sidecar gives one message starting with the file and the field, and naming the
// value where there is one.
TEST(SidecarReader, ThrowsInputErrorNamingTheFieldForEachInvalidValue) {
  struct Case {
    std::function<void(json&)> mutate;
    std::string expected_start;
  };
  const std::vector<Case> cases = {
      {[](json& v) { v = json::array(); }, "run1.json: expected a JSON object, got []"},
      {[](json& v) { v["format"] = "oscilab-recording/2"; },
       "run1.json: format: expected \"oscilab-recording/1\", got \"oscilab-recording/2\""},
      {[](json& v) { v["sample_rate_hz"] = -512; },
       "run1.json: sample_rate_hz: expected a positive number, got -512"},
      {[](json& v) { v["sample_rate_hz"] = 0; },
       "run1.json: sample_rate_hz: expected a positive number, got 0"},
      {[](json& v) { v["sample_rate_hz"] = "512"; },
       "run1.json: sample_rate_hz: expected a number, got \"512\""},
      {[](json& v) { v["sample_rate_hz"] = std::numeric_limits<double>::infinity(); },
       "run1.json: sample_rate_hz: expected a finite number"},
      {[](json& v) { v["mass_kg"] = 0.0; },
       "run1.json: mass_kg: expected a positive number, got 0.0"},
      // Values of the right form but no sense: checked against what a vibration test can have.
      {[](json& v) { v["mass_kg"] = 1e308; },
       "run1.json: mass_kg: 1e+308 kg is outside the range this field can have (1e-09 to "
       "1e+06 kg)"},
      {[](json& v) { v["mass_kg"] = 1e-12; }, "run1.json: mass_kg: 1e-12 kg is outside the range"},
      {[](json& v) { v["sample_rate_hz"] = 1e300; },
       "run1.json: sample_rate_hz: 1e+300 Hz is outside the range this field can have"},
      {[](json& v) { v["sample_rate_hz"] = 1e-9; },
       "run1.json: sample_rate_hz: 1e-09 Hz is outside the range"},
      {[](json& v) { v["excitation"]["frequency_hz"] = 300.0; },
       "run1.json: excitation.frequency_hz: 300 Hz is not below the Nyquist frequency, 256 Hz "
       "at sample_rate_hz 512"},
      {[](json& v) { v["excitation"]["frequency_hz"] = 1e9; },
       "run1.json: excitation.frequency_hz: 1e+09 Hz is not below the Nyquist frequency"},
      {[](json& v) { v["excitation"]["frequency_hz"] = 256.0; },  // exactly Nyquist
       "run1.json: excitation.frequency_hz: 256 Hz is not below the Nyquist frequency"},
      {[](json& v) { v["channels"] = json::array(); },
       "run1.json: channels: must list at least one channel"},
      {[](json& v) { v["channels"] = "y"; }, "run1.json: channels: expected an array, got \"y\""},
      {[](json& v) { v["channels"][1] = 3; }, "run1.json: channels[1]: expected an object, got 3"},
      {[](json& v) { v["channels"][1].erase("name"); },
       "run1.json: channels[1].name: missing required field"},
      {[](json& v) { v["channels"][1]["name"] = "base_acc"; },
       "run1.json: channels[1].name: duplicate name \"base_acc\" (also channels[0])"},
      {[](json& v) { v["channels"][1]["name"] = "t_s"; }, "run1.json: channels[1].name: \"t_s\""},
      {[](json& v) { v["channels"][1]["name"] = " y"; },
       "run1.json: channels[1].name: invalid name \" y\""},
      {[](json& v) { v["channels"][0]["role"] = "table"; },
       "run1.json: channels[0].role: unknown role \"table\""},
      {[](json& v) { v["channels"][0]["quantity"] = "jerk"; },
       "run1.json: channels[0].quantity: unknown quantity \"jerk\""},
      {[](json& v) { v["channels"][0]["quantity"] = "force"; },
       "run1.json: channels[0].quantity: quantity \"force\" does not fit role \"base\""},
      {[](json& v) { v["channels"][0]["unit"] = 1; },
       "run1.json: channels[0].unit: expected a string, got 1"},
      {[](json& v) { v["channels"][0]["scale"] = 0; },
       "run1.json: channels[0].scale: must not be zero"},
      // A scale takes a stored value into the channel's unit: a picometre per count (1e-12) to
      // 1e12; beyond, energies (products of two channels) overflow or the file is corrupt.
      {[](json& v) { v["channels"][1]["scale"] = 1e300; },
       "run1.json: channels[1].scale: 1e+300 is outside the magnitudes a calibration can have "
       "(1e-12 to 1e+12, either sign)"},
      {[](json& v) { v["channels"][0]["scale"] = -1e13; },
       "run1.json: channels[0].scale: -1e+13 is outside the magnitudes"},
      {[](json& v) { v["channels"][0]["scale"] = 1e-15; },
       "run1.json: channels[0].scale: 1e-15 is outside the magnitudes"},
      {[](json& v) { v["channels"][0]["offset"] = -1e200; },
       "run1.json: channels[0].offset: -1e+200 is outside the offsets a calibration can have (at "
       "most 1e+12 in magnitude)"},
      {[](json& v) { v["channels"][1]["ac_coupling_hz"] = 0.0; },
       "run1.json: channels[1].ac_coupling_hz: expected a positive number, got 0.0"},
      {[](json& v) { v["channels"][1]["ac_coupling_hz"] = "2 Hz"; },
       "run1.json: channels[1].ac_coupling_hz: expected a number, got \"2 Hz\""},
      {[](json& v) { v["channels"][1]["ac_coupling_hz"] = 256.0; },
       "run1.json: channels[1].ac_coupling_hz: 256 Hz is not below the Nyquist frequency, 256 "
       "Hz"},
      {[](json& v) { v["channels"][0]["full_scale_v"] = -5.0; },
       "run1.json: channels[0].full_scale_v: expected a positive number, got -5.0"},
      {[](json& v) { v["channels"][0].erase("scale"); },
       "run1.json: channels[0].scale: missing required field"},
      {[](json& v) { v["channels"][0]["offset"] = "0"; },
       "run1.json: channels[0].offset: expected a number, got \"0\""},
      {[](json& v) { v["channels"][0]["sensor"] = false; },
       "run1.json: channels[0].sensor: expected a string, got false"},
      {[](json& v) { v["channels"][0]["column"] = -1; },
       "run1.json: channels[0].column: expected a whole number from 0 to"},
      {[](json& v) { v["channels"][0]["column"] = 1.5; },
       "run1.json: channels[0].column: expected a whole number, got 1.5"},
      {[](json& v) {
         v["csv"] = {{"delimiter", ";;"}};
       },
       "run1.json: csv.delimiter: expected one character, got \";;\""},
      {[](json& v) {
         v["csv"] = {{"delimiter", "."}};
       },
       "run1.json: csv.delimiter: cannot split numbers on \".\""},
      {[](json& v) {
         v["csv"] = {{"header", "no"}};
       },
       "run1.json: csv.header: expected true or false, got \"no\""},
      {[](json& v) {
         v["csv"] = {{"delimeter", ","}};
       },
       "run1.json: csv.delimeter: unknown key"},
      {[](json& v) {
         v["csv"] = {{"header", false}};
       },
       "run1.json: channels[0].column: missing required field (csv.header is false)"},
      {[](json& v) {
         v["csv"] = {{"header", false}};
         v["channels"][0]["column"] = 2;
         v["channels"][1]["column"] = 2;
       },
       "run1.json: channels[1].column: 2 is also the column of channels[0]"},
      {[](json& v) { v["excitation"] = "sine"; },
       "run1.json: excitation: expected an object, got \"sine\""},
      {[](json& v) { v["excitation"]["frequency_hz"] = -9; },
       "run1.json: excitation.frequency_hz: expected a positive number, got -9"},
      {[](json& v) { v["excitation"]["levels"][0]["end_s"] = 0.0; },
       "run1.json: excitation.levels[0].end_s: must come after start_s (0.0), got 0.0"},
      {[](json& v) { v["excitation"]["levels"][0].erase("f0_n"); },
       "run1.json: excitation.levels[0].f0_n: missing required field"},
      {[](json& v) {
         v["excitation"]["levels"].push_back({{"f0_n", 0.4}, {"start_s", 5.0}, {"end_s", 20.0}});
       },
       "run1.json: excitation.levels[1].start_s: levels must follow each other in time"},
      {[](json& v) { v["notes"] = 42; }, "run1.json: notes: expected a string, got 42"},
  };
  for (const Case& test_case : cases) {
    json value = contract_example();
    test_case.mutate(value);
    const std::string message = parse_error_of(value);
    EXPECT_EQ(message.rfind(test_case.expected_start, 0), 0u)
        << "expected: " << test_case.expected_start << "\n     got: " << message;
  }
}

TEST(SidecarReader, AcceptsAPartialExcitationAndNullOptionals) {
  json value = contract_example();
  value["excitation"] = {{"type", "stepped-sine"}};
  value["mass_kg"] = nullptr;
  const Sidecar sidecar = parse_sidecar(value, "run1.json");
  ASSERT_TRUE(sidecar.excitation.has_value());
  EXPECT_FALSE(sidecar.excitation->frequency_hz.has_value());
  EXPECT_TRUE(sidecar.excitation->levels.empty());
  EXPECT_FALSE(sidecar.mass_kg.has_value());
  value.erase("excitation");
  value.erase("format");  // optional on read
  EXPECT_FALSE(parse_sidecar(value, "run1.json").excitation.has_value());
}

TEST(SidecarReader, AcceptsScalesAtTheEndsOfTheirRangeOfEitherSign) {
  json value = contract_example();
  value["channels"][0]["scale"] = 1e-12;  // a picometre per count
  value["channels"][1]["scale"] = -1e12;  // a sensor mounted the other way round
  value["channels"][1]["offset"] = 1e12;
  const Sidecar sidecar = parse_sidecar(value, "run1.json");
  EXPECT_EQ(sidecar.channels[0].scale, 1e-12);
  EXPECT_EQ(sidecar.channels[1].scale, -1e12);
}

TEST(UnitToSi, GivesTheSiFactorOfEachKnownUnit) {
  EXPECT_EQ(unit_to_si("m/s^2", Quantity::Acceleration, "x"), 1.0);
  EXPECT_EQ(unit_to_si("g", Quantity::Acceleration, "x"), 9.80665);  // standard gravity, exact
  EXPECT_EQ(unit_to_si("m/s", Quantity::Velocity, "x"), 1.0);
  EXPECT_EQ(unit_to_si("mm/s", Quantity::Velocity, "x"), 1e-3);
  EXPECT_EQ(unit_to_si("um/s", Quantity::Velocity, "x"), 1e-6);
  EXPECT_EQ(unit_to_si("m", Quantity::Displacement, "x"), 1.0);
  EXPECT_EQ(unit_to_si("mm", Quantity::Displacement, "x"), 1e-3);
  EXPECT_EQ(unit_to_si("um", Quantity::Displacement, "x"), 1e-6);
  EXPECT_EQ(unit_to_si("N", Quantity::Force, "x"), 1.0);
  EXPECT_EQ(unit_to_si("kN", Quantity::Force, "x"), 1e3);
  for (Quantity q :
       {Quantity::Acceleration, Quantity::Velocity, Quantity::Displacement, Quantity::Force}) {
    EXPECT_EQ(unit_to_si("V", q, "x"), 1.0);  // the scale is then the sensitivity per volt
  }
  EXPECT_EQ(input_error_of([] {
              unit_to_si("N", Quantity::Velocity, "f.json: u");
            }).rfind("f.json: u: unit \"N\" is a force unit, not one of velocity", 0),
            0u);
}

TEST(SidecarPath, HasTheStemOfTheRecordingAndJsonExtension) {
  EXPECT_EQ(sidecar_path_for("data/run1.wav"), "data/run1.json");
  EXPECT_EQ(sidecar_path_for("run1.flac"), "run1.json");
  EXPECT_EQ(sidecar_path_for("a.b/run.2.csv"), "a.b/run.2.json");
}

TEST(SidecarFile, WriteThenReadGivesTheSameSidecar) {
  const testing::TempDir dir;
  const Sidecar sidecar = parse_sidecar(contract_example(), "run1.json");
  write_sidecar(sidecar, dir.file("run1.json"));
  EXPECT_EQ(sidecar_to_json(read_sidecar(dir.file("run1.json"))), sidecar_to_json(sidecar));
  // The format key is always written, first.
  EXPECT_EQ(testing::read_file(dir.file("run1.json")).rfind("{\n  \"format\": ", 0), 0u);
}

TEST(SidecarFile, ThrowsInputErrorWhenFileIsMissingOrMalformed) {
  const testing::TempDir dir;
  const std::string path = dir.file("run1.json");
  std::string message = input_error_of([&] { read_sidecar(path); });
  EXPECT_EQ(message, path + ": file not found");
  testing::write_file(path, "{\"sample_rate_hz\": 512,");
  message = input_error_of([&] { read_sidecar(path); });
  EXPECT_EQ(message.rfind(path + ": malformed JSON: ", 0), 0u) << message;
}

TEST(SidecarFile, InvalidSidecarIsNotWrittenAndLeavesTheOldFile) {
  const testing::TempDir dir;
  const std::string path = dir.file("run1.json");
  Sidecar sidecar = parse_sidecar(contract_example(), "run1.json");
  write_sidecar(sidecar, path);
  const std::string before = testing::read_file(path);
  sidecar.channels[1].unit = "furlong";
  EXPECT_NE(input_error_of([&] { write_sidecar(sidecar, path); }).find("unknown unit"),
            std::string::npos);
  EXPECT_EQ(testing::read_file(path), before);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);
}

}  // namespace
}  // namespace oscilab::daq

namespace oscilab::daq {
namespace {

TEST(SidecarReader, KeepsWhereAFileOfNamedSignalsHoldsEachChannelAndItsTime) {
  json value = contract_example();
  value["channels"][0]["source"] = "analog/NI_9775/ai0";
  value["channels"][1]["source"] = "data";
  value["channels"][1]["column"] = 2;
  value["time"] = {{"source", "data"}, {"column", 0}};
  const Sidecar sidecar = parse_sidecar(value, "run1.json");
  EXPECT_EQ(sidecar.channels[0].source, "analog/NI_9775/ai0");
  EXPECT_EQ(sidecar.channels[1].column, 2);
  ASSERT_TRUE(sidecar.time.has_value());
  EXPECT_EQ(sidecar.time->source, "data");
  EXPECT_EQ(sidecar.time->column, 0);
  const Sidecar again = parse_sidecar(sidecar_to_json(sidecar), "again.json");
  EXPECT_EQ(sidecar_to_json(again), sidecar_to_json(sidecar));

  json empty_source = contract_example();
  empty_source["channels"][0]["source"] = "";
  EXPECT_EQ(parse_error_of(empty_source), "run1.json: channels[0].source: must not be empty");
  json time_in_csv = value;
  time_in_csv["csv"] = {{"header", true}};
  EXPECT_EQ(parse_error_of(time_in_csv),
            "run1.json: time: a CSV file names its time column in csv.time_column");
  json odd_time = value;
  odd_time["time"]["unit"] = "ms";
  EXPECT_EQ(parse_error_of(odd_time),
            "run1.json: time.unit: unknown key (expected source or column)");
  json no_source = value;
  no_source["time"] = {{"column", 0}};
  EXPECT_EQ(parse_error_of(no_source).rfind("run1.json: time", 0), 0u);
}

}  // namespace
}  // namespace oscilab::daq

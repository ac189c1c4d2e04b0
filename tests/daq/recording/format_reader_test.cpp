// The shared part of the readers of files that hold named signals (SignalFileReader::read: which
// signal each channel reads, lengths, the file's rate against the sidecar's, a time axis,
// calibration), the choice of a format by signature and extension, and the drafted sidecar.
// A reader with signals held in memory stands in for a format, so the mapping is tested apart
// from any file format.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/sidecar_draft.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::channel;
using testing::input_error_of;
using testing::TempDir;
using testing::write_file;

// Signals held in memory: `values[name]` is a vector, or a row-major matrix of signal.columns.
class MemorySignalReader final : public SignalFileReader {
 public:
  FileContents contents;
  std::map<std::string, std::vector<double>> values;

  std::string_view format_name() const override { return "memory"; }
  bool matches_signature(std::string_view) const override { return false; }
  bool matches_extension(std::string_view) const override { return false; }
  FileContents describe(const std::string&) const override { return contents; }
  std::vector<double> read_signal(const std::string&, const FileSignal& signal,
                                  int column) const override {
    const std::vector<double>& all = values.at(signal.name);
    if (column < 0) return all;
    std::vector<double> out;
    for (std::int64_t r = 0; r < signal.sample_count; ++r) {
      out.push_back(all[static_cast<std::size_t>(r * signal.columns + column)]);
    }
    return out;
  }

  void add(const std::string& name, std::vector<double> data, std::int64_t columns = 1,
           std::optional<double> rate_hz = std::nullopt) {
    FileSignal signal;
    signal.name = name;
    signal.columns = columns;
    signal.sample_count = static_cast<std::int64_t>(data.size()) / columns;
    signal.sample_rate_hz = rate_hz;
    contents.file_signals.push_back(signal);
    values[name] = std::move(data);
  }
};

std::vector<double> ramp(std::size_t count, double start, double step) {
  std::vector<double> out(count);
  for (std::size_t i = 0; i < count; ++i) out[i] = start + step * static_cast<double>(i);
  return out;
}

Sidecar two_channel_sidecar(double rate_hz) {
  Sidecar sidecar;
  sidecar.sample_rate_hz = rate_hz;
  sidecar.channels = {channel("acc", ChannelRole::Base, Quantity::Acceleration, "g", 2.0, 0.5),
                      channel("pos", ChannelRole::Mass, Quantity::Displacement, "mm", 1.0)};
  sidecar.channels[0].source = "group/acc";  // by source
  return sidecar;                            // "pos" by its own name
}

TEST(SignalFileReader, ReadsTheMappedSignalsAndCalibratesThem) {
  MemorySignalReader reader;
  reader.add("group/acc", ramp(100, -1.0, 0.02));
  reader.add("pos", ramp(100, 3.0, -0.5));
  const Recording recording = reader.read("mem", two_channel_sidecar(512.0), "s.json");
  ASSERT_EQ(recording.samples_si.rows(), 100);
  for (Eigen::Index r = 0; r < 100; ++r) {
    const double acc = -1.0 + 0.02 * static_cast<double>(r);
    const double pos = 3.0 - 0.5 * static_cast<double>(r);
    EXPECT_EQ(recording.samples_stored(r, 0), acc);
    EXPECT_EQ(recording.samples_stored(r, 1), pos);
    // (scale × stored + offset) × unit factor, the calibration every reader applies.
    EXPECT_EQ(recording.samples_si(r, 0), (2.0 * acc + 0.5) * 9.80665);
    EXPECT_EQ(recording.samples_si(r, 1), (1.0 * pos + 0.0) * 1e-3);
  }
}

TEST(SignalFileReader, PicksColumnsOfAMatrixAndChecksItsTimeColumn) {
  MemorySignalReader reader;
  // data: N × 3, columns t, x1, x2 (row-major in memory), t at 100 Hz from 2.5 s.
  std::vector<double> data;
  for (int r = 0; r < 50; ++r) {
    data.insert(data.end(), {2.5 + r / 100.0, 10.0 + r, -1.0 * r});
  }
  reader.add("data", data, 3);
  Sidecar sidecar = two_channel_sidecar(100.0);
  sidecar.channels[0].source = "data";
  sidecar.channels[0].column = 2;
  sidecar.channels[1].source = "data";
  sidecar.channels[1].column = 1;
  sidecar.time = SignalTime{"data", 0};
  const Recording recording = reader.read("mem", sidecar, "s.json");
  EXPECT_EQ(recording.samples_stored(49, 0), -49.0);
  EXPECT_EQ(recording.samples_stored(49, 1), 59.0);

  // Sample 20 skipped: the times no longer fit the rate.
  std::vector<double>& values = reader.values["data"];
  for (int r = 20; r < 50; ++r) values[static_cast<std::size_t>(3 * r)] += 0.01;
  EXPECT_EQ(input_error_of([&] { reader.read("mem", sidecar, "s.json"); }),
            "mem: \"data\", sample 20: time 2.71 s does not fit s.json's sample_rate_hz 100 "
            "(sample 20 should be at 2.7 s)");
}

TEST(SignalFileReader, TheFilesRateMustAgreeWithTheSidecarsToHalfASampleOverTheRecord) {
  // 1000 samples: at 512 Hz in the file, the drift against a sidecar rate r is
  // 1000 |1/512 − 1/r| s, allowed up to 0.5/r s: 512.2 Hz drifts 0.76 ms (< 0.98 ms), 512.3 Hz
  // 1.14 ms (> 0.98 ms).
  MemorySignalReader reader;
  reader.add("group/acc", ramp(1000, 0.0, 1.0), 1, 512.0);
  reader.add("pos", ramp(1000, 0.0, 1.0), 1, 512.0);
  EXPECT_NO_THROW(reader.read("mem", two_channel_sidecar(512.2), "s.json"));
  EXPECT_EQ(input_error_of([&] { reader.read("mem", two_channel_sidecar(512.3), "s.json"); }),
            "mem: \"group/acc\" is sampled at 512 Hz, s.json says sample_rate_hz 512.3");
}

TEST(SignalFileReader, RefusesWhatItCannotMap) {
  MemorySignalReader reader;
  reader.add("group/acc", ramp(10, 0.0, 1.0));
  reader.add("matrix", ramp(20, 0.0, 1.0), 2);
  reader.add("short", ramp(9, 0.0, 1.0));
  reader.add("empty", {});
  Sidecar sidecar = two_channel_sidecar(512.0);
  EXPECT_EQ(input_error_of([&] { reader.read("mem", sidecar, "s.json"); }),
            "mem: channel \"pos\" of s.json reads \"pos\", which the file does not hold (it "
            "holds \"group/acc\", \"matrix\", \"short\", \"empty\"; `oscilab-cli info` lists "
            "them)");
  sidecar.channels[1].source = "matrix";
  EXPECT_EQ(input_error_of([&] { reader.read("mem", sidecar, "s.json"); }),
            "mem: channel \"pos\" of s.json: \"matrix\" has 2 columns; the sidecar must pick one "
            "(\"column\")");
  sidecar.channels[1].column = 2;
  EXPECT_EQ(input_error_of([&] { reader.read("mem", sidecar, "s.json"); }),
            "mem: channel \"pos\" of s.json reads column 2 of \"matrix\", which has 2 columns "
            "(0-based)");
  sidecar.channels[1].source = "short";
  sidecar.channels[1].column = -1;
  EXPECT_EQ(input_error_of([&] { reader.read("mem", sidecar, "s.json"); }),
            "mem: \"short\" holds 9 samples, \"group/acc\" 10; a recording's channels have one "
            "length");
  sidecar.channels[1].source = "empty";
  EXPECT_EQ(input_error_of([&] { reader.read("mem", sidecar, "s.json"); }),
            "mem: channel \"pos\" of s.json: \"empty\" holds no samples");
}

TEST(FormatForFile, ChoosesBySignatureBeforeExtensionAndNamesTheFormatsItKnows) {
  TempDir dir;
  const std::string odd = dir.file("notes.xyz");
  write_file(odd, "hello");
  const std::string message = input_error_of([&] { format_for_file(odd); });
  EXPECT_EQ(message.rfind(odd + ": not a format Oscilab reads (it reads ", 0), 0u) << message;
  EXPECT_NE(message.find("CSV"), std::string::npos) << message;

  // A WAV header in a file named .csv is read as what it is.
  const std::string disguised = dir.file("really_a_wav.csv");
  write_file(disguised, std::string("RIFF\x24\x00\x00\x00WAVEfmt ", 16));
  EXPECT_EQ(&format_for_file(disguised), &sound_format());
}

TEST(SidecarDraft, GuessesRolesFromUnitsAndSpellsThemTheSidecarsWay) {
  FileContents contents;
  contents.file_signals = {FileSignal{"logger/time", 400, 1, "s", 200.0, "float64", {}},
                           FileSignal{"logger/laser", 400, 1, "mm/s", 200.0, "float64", {}},
                           FileSignal{"logger/table", 400, 1, "m/s\u00b2", 200.0, "float32", {}}};
  const SidecarDraft draft = draft_sidecar(contents);
  EXPECT_TRUE(draft.complete);
  const Sidecar sidecar = parse_sidecar(nlohmann::json(draft.sidecar), "draft");
  EXPECT_EQ(sidecar.sample_rate_hz, 200.0);
  ASSERT_EQ(sidecar.channels.size(), 2u);
  EXPECT_EQ(sidecar.channels[0].role, ChannelRole::Base);
  EXPECT_EQ(sidecar.channels[0].source, "logger/table");
  EXPECT_EQ(sidecar.channels[0].unit, "m/s^2");
  EXPECT_EQ(sidecar.channels[1].role, ChannelRole::Mass);
  EXPECT_EQ(sidecar.channels[1].quantity, Quantity::Velocity);
  EXPECT_EQ(sidecar.channels[1].unit, "mm/s");
  ASSERT_TRUE(sidecar.time.has_value());
  EXPECT_EQ(sidecar.time->source, "logger/time");
}

TEST(SidecarDraft, SaysWhatIsMissingWhenTheFileStatesNeitherUnitsNorRate) {
  FileContents contents;
  contents.file_signals = {FileSignal{"V1", 131072, 1, "", std::nullopt, "float64", {}},
                           FileSignal{"V2", 131072, 1, "", std::nullopt, "float64", {}}};
  const SidecarDraft draft = draft_sidecar(contents);
  EXPECT_FALSE(draft.complete);
  EXPECT_TRUE(draft.sidecar["sample_rate_hz"].is_null());
  EXPECT_EQ(draft.sidecar["channels"][0]["source"], "V1");
  EXPECT_EQ(draft.sidecar["channels"][0]["unit"], "V");
  EXPECT_EQ(draft.sidecar["channels"][1]["source"], "V2");
  std::string notes;
  for (const std::string& note : draft.notes) notes += note + "\n";
  EXPECT_NE(notes.find("sample_rate_hz: the file does not state it"), std::string::npos) << notes;
  EXPECT_NE(notes.find("channels[0].role: base, guessed from the order"), std::string::npos)
      << notes;
}

TEST(SidecarDraft, SpellsTheUsualUnitTextsAsTheSidecarDoes) {
  EXPECT_EQ(sidecar_unit_spelling(" m/s\u00b2 "), "m/s^2");
  EXPECT_EQ(sidecar_unit_spelling("m/s/s"), "m/s^2");
  EXPECT_EQ(sidecar_unit_spelling("Volts"), "V");
  EXPECT_EQ(sidecar_unit_spelling("\u03bcm"), "um");
  EXPECT_EQ(sidecar_unit_spelling("Pa"), "Pa");  // not a sidecar unit: unchanged
}

}  // namespace
}  // namespace oscilab::daq

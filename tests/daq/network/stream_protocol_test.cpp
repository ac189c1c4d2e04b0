#include "daq/network/stream_protocol.h"

#include "tests/daq/stream_test_layout.h"

#include <cmath>
#include <cstring>
#include <random>
#include <set>

#include <gtest/gtest.h>

namespace oscilab::daq {
namespace {

using namespace stream_protocol;

std::vector<std::uint8_t> sample_stream() {
  std::vector<std::uint8_t> bytes;
  append_hello({"id-1", testing::two_channel_layout()}, bytes);
  const double values[6] = {1.5, -2.0, 3.25, std::numeric_limits<double>::quiet_NaN(), 1e300, -0.0};
  append_data(7, 1024, 3, 2, values, bytes);
  append_event({12.5, EventKind::Level, "f0", {{"f0_n", 0.5}}}, bytes);
  append_bye(bytes);
  return bytes;
}

TEST(StreamProtocol, RoundTripsEveryFrameTypeWhateverTheSplit) {
  const std::vector<std::uint8_t> bytes = sample_stream();
  // Fed in one piece, byte by byte and in random pieces: TCP may split anywhere.
  for (int split : {0, 1, 2, 3}) {
    FrameDecoder decoder;
    std::mt19937 rng(static_cast<unsigned>(split));
    std::vector<Frame> frames;
    std::vector<std::vector<double>> data;
    std::size_t at = 0;
    while (at < bytes.size()) {
      const std::size_t n = split == 0 ? bytes.size() : split == 1 ? 1 : 1 + rng() % 17;
      const std::size_t take = std::min(n, bytes.size() - at);
      decoder.feed(bytes.data() + at, take);
      at += take;
      Frame frame;
      while (decoder.next(frame)) {
        if (frame.type == FrameType::Data) {
          std::vector<double> v;
          for (int i = 0; i < frame.rows * frame.channels; ++i)
            v.push_back(read_f64_le(frame.data + 8 * i));
          data.push_back(v);
        }
        frames.push_back(frame);
      }
      ASSERT_TRUE(decoder.error().empty()) << decoder.error();
    }
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_EQ(frames[0].hello->stream_id, "id-1");
    EXPECT_EQ(frames[0].hello->sidecar.channels[1].name, "y");
    EXPECT_EQ(frames[0].hello->sidecar.channels[0].scale, 3e-5);
    EXPECT_EQ(frames[1].sequence, 7u);
    EXPECT_EQ(frames[1].first_sample, 1024u);
    ASSERT_EQ(data.size(), 1u);
    EXPECT_EQ(data[0][0], 1.5);
    EXPECT_EQ(data[0][2], 3.25);
    EXPECT_TRUE(std::isnan(data[0][3]));  // bit-exact: NaN, huge and signed zero survive
    EXPECT_EQ(data[0][4], 1e300);
    EXPECT_TRUE(std::signbit(data[0][5]));
    EXPECT_EQ(frames[2].event->kind, EventKind::Level);
    EXPECT_EQ(frames[2].event->data["f0_n"], 0.5);
    EXPECT_EQ(frames[3].type, FrameType::Bye);
  }
}

std::string decode_error(std::vector<std::uint8_t> bytes) {
  FrameDecoder decoder;
  decoder.feed(bytes.data(), bytes.size());
  Frame frame;
  while (decoder.next(frame)) {
  }
  return decoder.error();
}

// Every kind crosses the wire by its name; a kind this program does not know keeps the sender's.
TEST(StreamProtocol, CarriesEveryEventKindByNameAndKeepsAnUnknownOne) {
  std::vector<StreamEvent> sent;
  for (int k = 0; k <= static_cast<int>(EventKind::Other); ++k) {
    sent.emplace_back(1.0, static_cast<EventKind>(k), "text");
  }
  sent.back().other_kind = "tare";
  std::vector<std::uint8_t> bytes;
  append_hello({"id-1", testing::two_channel_layout()}, bytes);
  for (const StreamEvent& event : sent) append_event(event, bytes);
  FrameDecoder decoder;
  decoder.feed(bytes.data(), bytes.size());
  Frame frame;
  ASSERT_TRUE(decoder.next(frame));  // HELLO
  std::set<std::string> names;
  for (const StreamEvent& event : sent) {
    ASSERT_TRUE(decoder.next(frame)) << decoder.error();
    ASSERT_TRUE(frame.event);
    EXPECT_EQ(frame.event->kind, event.kind) << event.kind_name();
    EXPECT_EQ(frame.event->kind_name(), event.kind_name());
    names.insert(event.kind_name());
  }
  EXPECT_EQ(names.size(), sent.size());  // no two kinds share a name
  EXPECT_EQ(sent.back().kind_name(), "tare");
  EXPECT_EQ(event_kind_from_string("non-finite"), EventKind::NonFinite);
  EXPECT_EQ(event_kind_from_string("no such kind"), EventKind::Other);
}

TEST(StreamProtocol, RejectsHostileFramesWithAReason) {
  std::vector<std::uint8_t> hello;
  append_hello({"id", testing::two_channel_layout()}, hello);

  std::vector<std::uint8_t> garbage(64, 0x41);
  EXPECT_NE(decode_error(garbage).find("bad magic"), std::string::npos);

  std::vector<std::uint8_t> huge = hello;  // a DATA header claiming 4 GiB
  const std::uint8_t header[12] = {'O', 'S', 'C', 'S', 1, 2, 0, 0, 0xff, 0xff, 0xff, 0xff};
  huge.insert(huge.end(), header, header + 12);
  EXPECT_NE(decode_error(huge).find("exceeds the limit"), std::string::npos);

  std::vector<std::uint8_t> no_hello;
  const double v[2] = {1, 2};
  append_data(0, 0, 1, 2, v, no_hello);
  EXPECT_EQ(decode_error(no_hello), "DATA before HELLO");

  std::vector<std::uint8_t> wrong_channels = hello;
  const double w[3] = {1, 2, 3};
  append_data(0, 0, 1, 3, w, wrong_channels);
  EXPECT_NE(decode_error(wrong_channels).find("3 channels, the HELLO said 2"), std::string::npos);

  std::vector<std::uint8_t> lying_length = hello;
  append_data(0, 0, 1, 2, v, lying_length);
  lying_length[hello.size() + 12 + 16] = 2;  // rows 2, but the payload holds 1
  EXPECT_NE(decode_error(lying_length).find("does not match"), std::string::npos);

  std::vector<std::uint8_t> version = hello;
  version[4] = 9;
  EXPECT_NE(decode_error(version).find("version 9"), std::string::npos);

  std::vector<std::uint8_t> bad_json = {'O', 'S', 'C', 'S', 1, 1, 0, 0, 3, 0, 0, 0, '{', 'x', '}'};
  EXPECT_EQ(decode_error(bad_json), "malformed JSON payload");

  Sidecar bad = testing::two_channel_layout();
  nlohmann::json j = {
      {"protocol", kProtocolName}, {"stream_id", "x"}, {"sidecar", sidecar_to_json(bad)}};
  j["sidecar"]["channels"][0]["unit"] = "furlong";
  const std::string text = j.dump();
  std::vector<std::uint8_t> bad_sidecar = {'O', 'S', 'C', 'S', 1, 1, 0, 0};
  for (int i = 0; i < 4; ++i)
    bad_sidecar.push_back(static_cast<std::uint8_t>(text.size() >> (8 * i)));
  bad_sidecar.insert(bad_sidecar.end(), text.begin(), text.end());
  EXPECT_NE(decode_error(bad_sidecar).find("unknown unit"), std::string::npos);
}

// A whole HELLO or EVENT frame of `text`, however it is nested.
std::vector<std::uint8_t> json_frame(FrameType type, const std::string& text) {
  std::vector<std::uint8_t> bytes = {'O', 'S', 'C', 'S', 1, static_cast<std::uint8_t>(type), 0, 0};
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(text.size() >> (8 * i)));
  bytes.insert(bytes.end(), text.begin(), text.end());
  return bytes;
}

TEST(StreamProtocol, RefusesAJsonDepthBombFrameAloneAndGoesOn) {
  // 100 000 nested arrays fit in 200 kB, under the frame limit; copied, they overflow the stack.
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::vector<std::uint8_t> bytes =
      json_frame(FrameType::Hello, "{\"protocol\": \"oscilab-stream/1\", \"junk\": " + deep + "}");
  append_hello({"id", testing::two_channel_layout()}, bytes);
  const std::vector<std::uint8_t> event =
      json_frame(FrameType::Event, "{\"kind\": \"mark\", \"data\": {\"x\": " + deep + "}}");
  bytes.insert(bytes.end(), event.begin(), event.end());
  const double values[2] = {1.0, 2.0};
  append_data(0, 0, 1, 2, values, bytes);

  FrameDecoder decoder;
  decoder.feed(bytes.data(), bytes.size());
  std::vector<Frame> frames;
  Frame frame;
  while (decoder.next(frame)) frames.push_back(frame);
  EXPECT_EQ(decoder.error(), "");
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[0].refused,
            "HELLO frame refused: JSON nested deeper than 64 levels (at byte 104)");
  EXPECT_TRUE(frames[1].refused.empty());
  EXPECT_TRUE(frames[1].hello.has_value());
  EXPECT_EQ(frames[2].refused,
            "EVENT frame refused: JSON nested deeper than 64 levels (at byte 93)");
  EXPECT_FALSE(frames[2].event.has_value());
  EXPECT_EQ(frames[3].type, FrameType::Data);  // the stream goes on after both
  EXPECT_EQ(frames[3].rows, 1);
}

// What a receiver acts on is checked against its clock: a level beyond Nyquist would hang the
// cycle analysis and be written into the sidecar; a time of 1e300 s is no sample index.
TEST(StreamEvent, ProblemNamesLevelsBeyondNyquistAndTimesBeyondAnyClock) {
  const auto level = [](nlohmann::json data) {
    return StreamEvent{1.0, EventKind::Level, "", std::move(data)};
  };
  EXPECT_EQ(stream_event_problem(level({{"f0_n", 0.5}, {"frequency_hz", 9.0}}), 512.0), "");
  EXPECT_EQ(stream_event_problem(level({{"f0_n", 0.5}, {"frequency_hz", 1e9}}), 512.0),
            "level event: frequency_hz 1e+09 is not in (0, 256) Hz (the Nyquist frequency of the "
            "512 Hz stream)");
  EXPECT_NE(stream_event_problem(level({{"frequency_hz", 256.0}}), 512.0), "");  // at Nyquist
  EXPECT_NE(stream_event_problem(level({{"frequency_hz", 0.0}}), 512.0), "");
  EXPECT_EQ(stream_event_problem(level({{"f0_n", -1.0}}), 512.0),
            "level event: f0_n -1 N is not a finite amplitude >= 0");
  EXPECT_EQ(stream_event_problem(level({{"f0_n", "x"}}), 512.0),
            "level event: f0_n is not a number: \"x\"");
  EXPECT_EQ(stream_event_problem(level({{"steady_to_s", 1e300}}), 512.0),
            "level event: steady_to_s 1e+300 is not a stream time in [0, 1e9] s");
  EXPECT_EQ(stream_event_problem(level({{"steady_from_s", 2.5}, {"steady_to_s", 1.5}}), 512.0),
            "level event: the steady window [2.5, 1.5) s ends before it starts");
  EXPECT_EQ(stream_event_problem(level({{"steady_from_s", 1.5}, {"steady_to_s", 2.5}}), 512.0), "");
  EXPECT_NE(stream_event_problem({1e300, EventKind::Discontinuity}, 512.0), "");
  EXPECT_NE(stream_event_problem({1.0, EventKind::Invalid, "", {{"from_s", -5.0}}}, 512.0), "");
  // No time (NaN) is allowed; kinds only logged are never refused.
  EXPECT_EQ(stream_event_problem({std::nan(""), EventKind::Discontinuity}, 512.0), "");
  EXPECT_EQ(stream_event_problem({1e300, EventKind::Mark, "", {{"f0_n", "x"}}}, 512.0), "");
}

TEST(StreamProtocol, RandomBytesNeverCrashAndMemoryStaysBounded) {
  // 2000 streams of random bytes after a valid HELLO, some with a valid prefix: the decoder
  // either waits for more or reports an error; it never reads past what it was given (ASan
  // build) and never buffers more than one frame's limit.
  std::mt19937 rng(7);
  std::vector<std::uint8_t> hello;
  append_hello({"id", testing::two_channel_layout()}, hello);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<std::uint8_t> bytes = trial % 2 ? hello : std::vector<std::uint8_t>{};
    const std::size_t n = rng() % 300;
    for (std::size_t i = 0; i < n; ++i) bytes.push_back(static_cast<std::uint8_t>(rng()));
    if (trial % 3 == 0 && bytes.size() > hello.size() + 4) {
      std::memcpy(bytes.data() + hello.size(), kMagic, 4);  // a plausible header
    }
    FrameDecoder decoder;
    decoder.feed(bytes.data(), bytes.size());
    Frame frame;
    int frames = 0;
    while (decoder.next(frame)) ++frames;
    EXPECT_LE(frames, 1 + static_cast<int>(n / 12));
  }
}

}  // namespace
}  // namespace oscilab::daq

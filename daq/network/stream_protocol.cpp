#include "daq/network/stream_protocol.h"

#include <bit>
#include <cstring>
#include <string_view>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"

namespace oscilab::daq::stream_protocol {
namespace {

void put_u16(std::uint16_t v, std::vector<std::uint8_t>& out) {
  out.push_back(static_cast<std::uint8_t>(v));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_u32(std::uint32_t v, std::vector<std::uint8_t>& out) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_u64(std::uint64_t v, std::vector<std::uint8_t>& out) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
std::uint32_t get_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}
std::uint64_t get_u64(const std::uint8_t* p) {
  return static_cast<std::uint64_t>(get_u32(p)) | static_cast<std::uint64_t>(get_u32(p + 4)) << 32;
}

void put_header(FrameType type, std::size_t payload_bytes, std::vector<std::uint8_t>& out) {
  out.insert(out.end(), kMagic, kMagic + 4);
  out.push_back(kVersion);
  out.push_back(static_cast<std::uint8_t>(type));
  put_u16(0, out);
  put_u32(static_cast<std::uint32_t>(payload_bytes), out);
}

void append_json(FrameType type, const nlohmann::json& value, std::vector<std::uint8_t>& out) {
  const std::string text = value.dump();
  if (text.size() > kMaxJsonBytes) {
    throw InputError("stream: a " + std::string(type == FrameType::Hello ? "HELLO" : "EVENT") +
                     " frame of " + std::to_string(text.size()) + " bytes exceeds the protocol's " +
                     std::to_string(kMaxJsonBytes));
  }
  put_header(type, text.size(), out);
  out.insert(out.end(), text.begin(), text.end());
}

}  // namespace

double read_f64_le(const std::uint8_t* bytes) {
  const std::uint64_t bits = get_u64(bytes);
  return std::bit_cast<double>(bits);
}

void append_hello(const Hello& hello, std::vector<std::uint8_t>& out) {
  append_json(FrameType::Hello,
              {{"protocol", kProtocolName},
               {"stream_id", hello.stream_id},
               {"sidecar", sidecar_to_json(hello.sidecar)}},
              out);
}

void append_data(std::uint64_t sequence, std::uint64_t first_sample, int rows, int channels,
                 const double* values, std::vector<std::uint8_t>& out) {
  if (rows < 1 || static_cast<std::uint32_t>(rows) > kMaxRows || channels < 1 ||
      static_cast<std::uint32_t>(channels) > kMaxChannels) {
    throw InputError("stream: a DATA frame holds 1.." + std::to_string(kMaxRows) + " rows of 1.." +
                     std::to_string(kMaxChannels) + " channels, got " + std::to_string(rows) +
                     " × " + std::to_string(channels));
  }
  const std::size_t count = static_cast<std::size_t>(rows) * static_cast<std::size_t>(channels);
  put_header(FrameType::Data, kDataHeaderBytes + 8 * count, out);
  put_u64(sequence, out);
  put_u64(first_sample, out);
  put_u32(static_cast<std::uint32_t>(rows), out);
  put_u32(static_cast<std::uint32_t>(channels), out);
  for (std::size_t i = 0; i < count; ++i) put_u64(std::bit_cast<std::uint64_t>(values[i]), out);
}

void append_event(const StreamEvent& event, std::vector<std::uint8_t>& out) {
  append_json(FrameType::Event, event.to_json(), out);
}

void append_bye(std::vector<std::uint8_t>& out) { put_header(FrameType::Bye, 0, out); }

void FrameDecoder::feed(const std::uint8_t* bytes, std::size_t count) {
  if (consumed_ > 0 && consumed_ >= buffer_.size() / 2) {  // compact, keeping memory bounded
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(consumed_));
    consumed_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes, bytes + count);
}

bool FrameDecoder::fail(const std::string& message) {
  error_ = message;
  return false;
}

bool FrameDecoder::next(Frame& frame) {
  if (!error_.empty()) return false;
  const std::size_t available = buffer_.size() - consumed_;
  if (available < kHeaderBytes) return false;
  const std::uint8_t* header = buffer_.data() + consumed_;
  if (std::memcmp(header, kMagic, 4) != 0) return fail("bad magic (not an Oscilab stream)");
  if (header[4] != kVersion) {
    return fail("protocol version " + std::to_string(header[4]) + " (this receiver speaks 1)");
  }
  const std::uint8_t type = header[5];
  const std::uint32_t length = get_u32(header + 8);
  if (type < 1 || type > 4) return fail("unknown frame type " + std::to_string(type));
  const auto frame_type = static_cast<FrameType>(type);
  const std::uint32_t limit = (frame_type == FrameType::Data)  ? kMaxPayloadBytes
                              : (frame_type == FrameType::Bye) ? 0
                                                               : kMaxJsonBytes;
  if (length > limit) {
    return fail("frame of " + std::to_string(length) + " bytes exceeds the limit of " +
                std::to_string(limit));
  }
  if (available < kHeaderBytes + length) return false;  // wait for the rest
  const std::uint8_t* payload = header + kHeaderBytes;
  frame = Frame{};
  frame.type = frame_type;

  if (frame_type == FrameType::Hello || frame_type == FrameType::Event) {
    const std::string_view text(reinterpret_cast<const char*>(payload), length);
    const char* name = frame_type == FrameType::Hello ? "HELLO" : "EVENT";
    // A value nested too deep would overflow the stack when copied: the frame is whole, so it
    // is refused alone and the stream goes on.
    if (const std::string violation = json_limit_violation(text); !violation.empty()) {
      consumed_ += kHeaderBytes + length;
      frame.refused = std::string(name) + " frame refused: " + violation;
      return true;
    }
    nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
    if (value.is_discarded() || !value.is_object()) return fail("malformed JSON payload");
    if (frame_type == FrameType::Hello) {
      if (value.value("protocol", std::string()) != kProtocolName) {
        return fail("HELLO: protocol must be \"" + std::string(kProtocolName) + "\"");
      }
      Hello hello;
      const auto id = value.find("stream_id");
      if (id == value.end() || !id->is_string()) return fail("HELLO: stream_id missing");
      hello.stream_id = id->get<std::string>();
      const auto sidecar = value.find("sidecar");
      if (sidecar == value.end()) return fail("HELLO: sidecar missing");
      try {
        hello.sidecar = parse_sidecar(*sidecar, "HELLO sidecar");
      } catch (const InputError& error) {
        return fail(error.what());
      }
      if (hello.sidecar.channels.size() > kMaxChannels) return fail("HELLO: too many channels");
      channels_ = static_cast<int>(hello.sidecar.channels.size());
      frame.hello = std::move(hello);
    } else {
      StreamEvent event;
      const auto t = value.find("t_s");
      event.t_s = (t != value.end() && t->is_number()) ? t->get<double>()
                                                       : std::numeric_limits<double>::quiet_NaN();
      const auto kind = value.find("kind");
      if (kind == value.end() || !kind->is_string()) return fail("EVENT: kind missing");
      event.kind = event_kind_from_string(kind->get<std::string>());
      if (event.kind == EventKind::Other) event.other_kind = kind->get<std::string>();
      if (const auto text = value.find("text"); text != value.end() && text->is_string()) {
        event.text = text->get<std::string>();
      }
      if (const auto data = value.find("data"); data != value.end() && data->is_object()) {
        event.data = *data;
      }
      frame.event = std::move(event);
    }
  } else if (frame_type == FrameType::Data) {
    if (channels_ == 0) return fail("DATA before HELLO");
    if (length < kDataHeaderBytes) return fail("DATA frame shorter than its header");
    frame.sequence = get_u64(payload);
    frame.first_sample = get_u64(payload + 8);
    const std::uint32_t rows = get_u32(payload + 16);
    const std::uint32_t channels = get_u32(payload + 20);
    if (rows < 1 || rows > kMaxRows) return fail("DATA: " + std::to_string(rows) + " rows");
    if (channels != static_cast<std::uint32_t>(channels_)) {
      return fail("DATA: " + std::to_string(channels) + " channels, the HELLO said " +
                  std::to_string(channels_));
    }
    if (length != kDataHeaderBytes + 8ull * rows * channels) {
      return fail("DATA: length " + std::to_string(length) + " does not match " +
                  std::to_string(rows) + " rows × " + std::to_string(channels) + " channels");
    }
    frame.rows = static_cast<int>(rows);
    frame.channels = static_cast<int>(channels);
    frame.data = payload + kDataHeaderBytes;
  }
  consumed_ += kHeaderBytes + length;
  return true;
}

}  // namespace oscilab::daq::stream_protocol

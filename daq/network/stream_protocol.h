#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "daq/recording/sidecar.h"
#include "daq/sources/raw_block.h"
#include "daq/sources/stream_event.h"

namespace oscilab::daq {

/// The Oscilab stream protocol, version 1 (docs/stream-protocol.md): frames over TCP, each
///   "OSCS" | version u8 = 1 | type u8 | reserved u16 = 0 | payload length u32 | payload
/// little-endian. A sender opens with HELLO (JSON: protocol, stream_id, sidecar), then sends
/// DATA frames (u64 sequence, u64 first_sample, u32 rows, u32 channels, rows × channels f64
/// stored values, row-major), EVENT frames (JSON stream events) and ends with BYE.
namespace stream_protocol {

inline constexpr char kMagic[4] = {'O', 'S', 'C', 'S'};
inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::size_t kHeaderBytes = 12;
inline constexpr std::size_t kDataHeaderBytes = 24;
inline constexpr std::uint32_t kMaxJsonBytes = 1u << 20;  // HELLO and EVENT payloads
inline constexpr std::uint32_t kMaxRows = 1024;           // per DATA frame (2 s at 512 Hz)
inline constexpr std::uint32_t kMaxChannels = 16;
inline constexpr std::uint32_t kMaxPayloadBytes =
    static_cast<std::uint32_t>(kDataHeaderBytes) + kMaxRows * kMaxChannels * 8u;  // 128 KiB + 24
inline constexpr const char* kProtocolName = "oscilab-stream/1";

enum class FrameType : std::uint8_t { Hello = 1, Data = 2, Event = 3, Bye = 4 };

struct Hello {
  std::string stream_id;  // the same across reconnections of one stream
  Sidecar sidecar;
};

/// Encoders append one whole frame to `out`.
void append_hello(const Hello& hello, std::vector<std::uint8_t>& out);
void append_data(std::uint64_t sequence, std::uint64_t first_sample, int rows, int channels,
                 const double* values, std::vector<std::uint8_t>& out);
void append_event(const StreamEvent& event, std::vector<std::uint8_t>& out);
void append_bye(std::vector<std::uint8_t>& out);

/// One decoded frame. For DATA the samples are left in the decoder's buffer: data_values()
/// reads them (valid until the next feed/next call).
struct Frame {
  FrameType type = FrameType::Bye;
  std::optional<Hello> hello;
  std::optional<StreamEvent> event;
  std::uint64_t sequence = 0, first_sample = 0;
  int rows = 0, channels = 0;
  const std::uint8_t* data = nullptr;  // rows × channels little-endian f64
  // Non-empty: a whole frame whose content was refused (why, in one line); nothing else is set
  // and the stream goes on with the next frame.
  std::string refused;
};

/// Incremental, defensive decoder: bytes in (any split), frames out. Every violation (bad magic
/// or version, unknown type, a length over the limits, a DATA frame whose sizes disagree or whose
/// channel count differs from the HELLO, malformed JSON or sidecar, DATA before HELLO) is a
/// protocol error: next() returns false with error() set, and the connection must be closed (the
/// byte stream cannot be resynchronised). A whole frame whose content is refused (JSON nested
/// beyond kMaxJsonDepth) is returned with `refused` set: the stream goes on. Memory is bounded by
/// kMaxPayloadBytes.
class FrameDecoder {
 public:
  /// Appends received bytes.
  void feed(const std::uint8_t* bytes, std::size_t count);
  /// Decodes the next complete frame into `frame`. False when none is complete yet (error()
  /// empty) or on a protocol error (error() says what).
  bool next(Frame& frame);
  const std::string& error() const { return error_; }
  /// Channel count of the HELLO seen, 0 before.
  int channels() const { return channels_; }

 private:
  bool fail(const std::string& message);

  std::vector<std::uint8_t> buffer_;
  std::size_t consumed_ = 0;  // bytes of buffer_ already decoded
  std::string error_;
  int channels_ = 0;
};

/// Little-endian f64 at `bytes` (the protocol's byte order on any host).
double read_f64_le(const std::uint8_t* bytes);

}  // namespace stream_protocol
}  // namespace oscilab::daq

#pragma once

// Byte-level building blocks of TDMS files for the tests and benchmarks, after NI's "TDMS File
// Format Internal Structure". They only append numbers and strings in a segment's byte order;
// each fixture spells out its fields itself, with a comment on each.

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

namespace oscilab::daq::testing {

// ToC flags of the lead-in.
inline constexpr std::uint32_t kTocMetaData = 1u << 1;
inline constexpr std::uint32_t kTocNewObjList = 1u << 2;
inline constexpr std::uint32_t kTocRawData = 1u << 3;
inline constexpr std::uint32_t kTocInterleavedData = 1u << 5;
inline constexpr std::uint32_t kTocBigEndian = 1u << 6;
inline constexpr std::uint32_t kTocDAQmxRawData = 1u << 7;

// tdsDataType codes.
inline constexpr std::uint32_t kTdsI8 = 0x01;
inline constexpr std::uint32_t kTdsI16 = 0x02;
inline constexpr std::uint32_t kTdsI32 = 0x03;
inline constexpr std::uint32_t kTdsI64 = 0x04;
inline constexpr std::uint32_t kTdsU8 = 0x05;
inline constexpr std::uint32_t kTdsU16 = 0x06;
inline constexpr std::uint32_t kTdsU32 = 0x07;
inline constexpr std::uint32_t kTdsU64 = 0x08;
inline constexpr std::uint32_t kTdsF32 = 0x09;
inline constexpr std::uint32_t kTdsF64 = 0x0A;
inline constexpr std::uint32_t kTdsString = 0x20;
inline constexpr std::uint32_t kTdsBoolean = 0x21;
inline constexpr std::uint32_t kTdsTimestamp = 0x44;
inline constexpr std::uint32_t kTdsFixedPoint = 0x4F;
inline constexpr std::uint32_t kTdsComplex128 = 0x10000D;
inline constexpr std::uint32_t kTdsDaqmxRaw = 0xFFFFFFFF;

// Raw data index headers.
inline constexpr std::uint32_t kIndexSameAsPrevious = 0x00000000;
inline constexpr std::uint32_t kIndexNoData = 0xFFFFFFFF;
inline constexpr std::uint32_t kIndexPlain = 20;         // length of a plain index
inline constexpr std::uint32_t kIndexPlainStrings = 28;  // length of an index of strings
inline constexpr std::uint32_t kIndexFormatChangingScaler = 0x00001269;
inline constexpr std::uint32_t kIndexDigitalLineScaler = 0x0000126A;

/// Bytes in one byte order.
class TdmsBytes {
 public:
  explicit TdmsBytes(bool big_endian = false) : big_endian_(big_endian) {}

  template <typename T>
  TdmsBytes& number(T value) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    const bool swap = big_endian_ != (std::endian::native == std::endian::big);
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      bytes_.push_back(static_cast<char>(raw[swap ? sizeof(T) - 1 - i : i]));
    }
    return *this;
  }
  TdmsBytes& u8(std::uint8_t value) { return number(value); }
  TdmsBytes& u32(std::uint32_t value) { return number(value); }
  TdmsBytes& u64(std::uint64_t value) { return number(value); }
  TdmsBytes& i32(std::int32_t value) { return number(value); }
  TdmsBytes& f64(double value) { return number(value); }
  /// A string: its length in bytes (u32), then its UTF-8 bytes.
  TdmsBytes& str(const std::string& text) {
    u32(static_cast<std::uint32_t>(text.size()));
    bytes_ += text;
    return *this;
  }
  TdmsBytes& raw(const std::string& bytes) {
    bytes_ += bytes;
    return *this;
  }

  const std::string& bytes() const { return bytes_; }
  std::size_t size() const { return bytes_.size(); }

 private:
  bool big_endian_;
  std::string bytes_;
};

/// A 28-byte lead-in: "TDSm", the ToC (always little-endian), then the version, the next-segment
/// offset and the raw-data offset (both counted from the end of the lead-in) in the segment's
/// byte order.
inline std::string tdms_lead_in(std::uint32_t toc, std::uint32_t version,
                                std::uint64_t next_segment_offset, std::uint64_t raw_data_offset) {
  TdmsBytes toc_bytes(false);
  toc_bytes.u32(toc);
  TdmsBytes rest((toc & kTocBigEndian) != 0);
  rest.u32(version).u64(next_segment_offset).u64(raw_data_offset);
  return "TDSm" + toc_bytes.bytes() + rest.bytes();
}

/// A whole segment: a version 4713 lead-in whose offsets fit `metadata` and `raw`, then both.
inline std::string tdms_segment(std::uint32_t toc, const std::string& metadata,
                                const std::string& raw) {
  return tdms_lead_in(toc, 4713, metadata.size() + raw.size(), metadata.size()) + metadata + raw;
}

}  // namespace oscilab::daq::testing

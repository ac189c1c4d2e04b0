#pragma once

// The encodings inside a TDMS segment's metadata: numbers in the segment's byte order,
// length-prefixed strings, object paths, property values and timestamps.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "daq/recording/formats/tdms_values.h"

namespace oscilab::daq::tdms {

// Reads one segment's metadata from a buffer.
class MetadataCursor {
 public:
  MetadataCursor(const std::vector<unsigned char>& bytes, std::uint64_t file_offset,
                 bool big_endian, std::function<void(const std::string&)> fail)
      : bytes_(bytes), file_offset_(file_offset), big_endian_(big_endian), fail_(std::move(fail)) {}

  bool big_endian() const { return big_endian_; }
  std::size_t remaining() const { return bytes_.size() - position_; }
  std::size_t position() const { return position_; }
  std::uint64_t file_position() const { return file_offset_ + position_; }

  const unsigned char* take(std::size_t count, const char* what) {
    if (count > remaining()) {
      fail_(std::string(what) + " at byte " + std::to_string(file_position()) + " needs " +
            std::to_string(count) + " bytes, the metadata has " + std::to_string(remaining()) +
            " left");
    }
    const unsigned char* at = bytes_.data() + position_;
    position_ += count;
    return at;
  }
  void skip(std::size_t count, const char* what) { take(count, what); }

  template <typename T>
  T number(const char* what) {
    return load<T>(take(sizeof(T), what), big_endian_);
  }
  std::uint32_t u32(const char* what) { return number<std::uint32_t>(what); }
  std::uint64_t u64(const char* what) { return number<std::uint64_t>(what); }

  std::string string(const char* what) {
    const std::uint32_t length = u32(what);
    const unsigned char* text = take(length, what);
    return std::string(reinterpret_cast<const char*>(text), length);
  }

 private:
  const std::vector<unsigned char>& bytes_;
  std::uint64_t file_offset_;
  bool big_endian_;
  std::function<void(const std::string&)> fail_;
  std::size_t position_ = 0;
};

/// `text` with every byte sequence that is not UTF-8 replaced by U+FFFD, so that names and
/// properties can go into JSON.
std::string valid_utf8(std::string_view text);

/// A TDMS timestamp (seconds since 1904-01-01 00:00 UTC and 2^-64 fractions of a second) as ISO
/// 8601 UTC text with microseconds.
std::string timestamp_text(std::int64_t seconds, std::uint64_t fraction);

/// Splits "/'group'/'channel'" into its names ('' stands for one quote); false if malformed.
bool split_path(std::string_view path, std::vector<std::string>& names);

/// The value of a property of data type `type` at the cursor, or nothing when values of that
/// type are not read.
std::optional<nlohmann::json> read_property_value(MetadataCursor& cursor, std::uint32_t type);

}  // namespace oscilab::daq::tdms

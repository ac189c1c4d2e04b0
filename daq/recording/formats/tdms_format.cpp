// NI TDMS files, read from NI's "TDMS File Format Internal Structure". A file is a chain of
// segments; each has a 28-byte lead-in (tag "TDSm", table of contents, version, next-segment and
// raw-data offsets), optional metadata (objects with their raw data indexes and properties) and
// raw data in chunks. describe() reads lead-ins and metadata only and seeks over the raw data;
// read_signal() walks the same metadata again and reads one channel's values where they lie.
//
// Memory stays proportional to the metadata and to the values asked for: the layout of the
// current segment is kept, not one per segment, and every declared count is checked against the
// bytes that can hold it before anything is allocated.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <unordered_map>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

// Table of contents flags of the lead-in.
constexpr std::uint32_t kTocMetaData = 1u << 1;
constexpr std::uint32_t kTocNewObjList = 1u << 2;
constexpr std::uint32_t kTocRawData = 1u << 3;
constexpr std::uint32_t kTocInterleavedData = 1u << 5;
constexpr std::uint32_t kTocBigEndian = 1u << 6;
constexpr std::uint32_t kTocDAQmxRawData = 1u << 7;

constexpr std::uint64_t kLeadInBytes = 28;
// The next-segment offset of a segment whose writer did not finish it.
constexpr std::uint64_t kLengthUnknown = 0xFFFFFFFFFFFFFFFFull;

// Raw data index headers.
constexpr std::uint32_t kIndexSameAsPrevious = 0x00000000;
constexpr std::uint32_t kIndexNoData = 0xFFFFFFFF;
constexpr std::uint32_t kIndexFormatChangingScaler = 0x00001269;
constexpr std::uint32_t kIndexDigitalLineScaler = 0x0000126A;

constexpr std::uint32_t kTypeString = 0x20;
constexpr std::uint32_t kTypeBoolean = 0x21;
constexpr std::uint32_t kTypeTimestamp = 0x44;
constexpr std::uint32_t kTypeComplex64 = 0x08000C;
constexpr std::uint32_t kTypeComplex128 = 0x10000D;
constexpr std::uint32_t kTypeDaqmxRaw = 0xFFFFFFFF;
// The input source of a scale that reads the stored (raw) values.
constexpr std::uint32_t kScaleInputRaw = 0xFFFFFFFF;

constexpr std::size_t kReadBlockBytes = std::size_t{1} << 20;  // at most this read at once

// The numeric types a signal's values can have.
enum class Sample { I8, I16, I32, I64, U8, U16, U32, U64, F32, F64 };

// A tdsDataType: its name, its size in the raw data (0: not fixed or not documented) and, for
// the numeric ones, how its values are read.
struct TypeInfo {
  std::uint32_t code;
  const char* name;
  std::uint32_t size_bytes;
  std::optional<Sample> sample;
};

constexpr TypeInfo kTypes[] = {
    {0x00, "void", 0, std::nullopt},
    {0x01, "int8", 1, Sample::I8},
    {0x02, "int16", 2, Sample::I16},
    {0x03, "int32", 4, Sample::I32},
    {0x04, "int64", 8, Sample::I64},
    {0x05, "uint8", 1, Sample::U8},
    {0x06, "uint16", 2, Sample::U16},
    {0x07, "uint32", 4, Sample::U32},
    {0x08, "uint64", 8, Sample::U64},
    {0x09, "float32", 4, Sample::F32},
    {0x0A, "float64", 8, Sample::F64},
    {0x0B, "extended float", 0, std::nullopt},
    {0x19, "float32 with unit", 4, Sample::F32},
    {0x1A, "float64 with unit", 8, Sample::F64},
    {0x1B, "extended float with unit", 0, std::nullopt},
    {kTypeString, "string", 0, std::nullopt},
    {kTypeBoolean, "boolean", 1, std::nullopt},
    {kTypeTimestamp, "timestamp", 16, std::nullopt},
    {0x4F, "fixed-point", 0, std::nullopt},
    {kTypeComplex64, "complex64", 8, std::nullopt},
    {kTypeComplex128, "complex128", 16, std::nullopt},
};

// The data types of DAQmx scalers, an enumeration of their own.
constexpr TypeInfo kDaqmxTypes[] = {
    {0, "uint8", 1, Sample::U8},    {1, "int8", 1, Sample::I8},    {2, "uint16", 2, Sample::U16},
    {3, "int16", 2, Sample::I16},   {4, "uint32", 4, Sample::U32}, {5, "int32", 4, Sample::I32},
    {6, "uint64", 8, Sample::U64},  {7, "int64", 8, Sample::I64},  {8, "float32", 4, Sample::F32},
    {9, "float64", 8, Sample::F64},
};

std::string hex(std::uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof text, "0x%llX", static_cast<unsigned long long>(value));
  return text;
}

const TypeInfo* type_info(std::uint32_t code) {
  for (const TypeInfo& type : kTypes) {
    if (type.code == code) return &type;
  }
  return nullptr;
}

const TypeInfo* daqmx_type_info(std::uint32_t code) {
  for (const TypeInfo& type : kDaqmxTypes) {
    if (type.code == code) return &type;
  }
  return nullptr;
}

std::string type_name(std::uint32_t code) {
  const TypeInfo* type = type_info(code);
  return type ? std::string(type->name) + " (" + hex(code) + ")" : "unknown (" + hex(code) + ")";
}

// `text` with every byte sequence that is not UTF-8 replaced by U+FFFD, so that names and
// properties can go into JSON.
std::string valid_utf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t length = 0;
    std::uint32_t code = 0;
    if (c < 0x80) {
      length = 1;
      code = c;
    } else if ((c & 0xE0) == 0xC0) {
      length = 2;
      code = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      length = 3;
      code = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      length = 4;
      code = c & 0x07;
    }
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      valid = (next & 0xC0) == 0x80;
      code = (code << 6) | (next & 0x3F);
    }
    constexpr std::uint32_t kMinimum[] = {0, 0, 0x80, 0x800, 0x10000};
    valid =
        valid && code >= kMinimum[length] && code <= 0x10FFFF && (code < 0xD800 || code > 0xDFFF);
    if (valid) {
      out.append(text.substr(i, length));
      i += length;
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

// A TDMS timestamp (seconds since 1904-01-01 00:00 UTC and 2^-64 fractions of a second) as ISO
// 8601 UTC text with microseconds.
std::string timestamp_text(std::int64_t seconds, std::uint64_t fraction) {
  constexpr std::int64_t kUnixMinus1904_s = 2082844800;
  constexpr std::int64_t kLimit_s = 100000000000;  // ±3000 years: beyond, the raw numbers
  if (seconds < -kLimit_s || seconds > kLimit_s) {
    return "1904-01-01T00:00:00Z + " + std::to_string(seconds) + " s";
  }
  const std::int64_t unix_s = seconds - kUnixMinus1904_s;
  std::int64_t days = unix_s / 86400;
  std::int64_t second_of_day = unix_s % 86400;
  if (second_of_day < 0) {
    second_of_day += 86400;
    --days;
  }
  // Civil date from days since 1970-01-01 (H. Hinnant, "chrono-Compatible Low-Level Date
  // Algorithms", civil_from_days).
  const std::int64_t z = days + 719468;
  const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  const std::int64_t day = doy - (153 * mp + 2) / 5 + 1;
  const std::int64_t month = mp < 10 ? mp + 3 : mp - 9;
  const std::int64_t year = yoe + era * 400 + (month <= 2 ? 1 : 0);
  const std::uint64_t microseconds = ((fraction >> 32) * 1000000) >> 32;
  char text[64];
  std::snprintf(
      text, sizeof text, "%04lld-%02lld-%02lldT%02lld:%02lld:%02lld.%06lluZ",
      static_cast<long long>(year), static_cast<long long>(month), static_cast<long long>(day),
      static_cast<long long>(second_of_day / 3600), static_cast<long long>(second_of_day / 60 % 60),
      static_cast<long long>(second_of_day % 60), static_cast<unsigned long long>(microseconds));
  return text;
}

template <typename U>
U byte_swapped(U value) {
  if constexpr (sizeof(U) == 1) {
    return value;
  } else if constexpr (sizeof(U) == 2) {
    return static_cast<U>(__builtin_bswap16(value));
  } else if constexpr (sizeof(U) == 4) {
    return __builtin_bswap32(value);
  } else {
    return __builtin_bswap64(value);
  }
}

// A value of type T stored at `bytes` in the given byte order.
template <typename T>
T load(const unsigned char* bytes, bool big_endian) {
  using U = std::conditional_t<
      sizeof(T) == 1, std::uint8_t,
      std::conditional_t<sizeof(T) == 2, std::uint16_t,
                         std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
  U raw;
  std::memcpy(&raw, bytes, sizeof raw);
  if (big_endian != (std::endian::native == std::endian::big)) raw = byte_swapped(raw);
  T value;
  std::memcpy(&value, &raw, sizeof value);
  return value;
}

// Appends `count` values of type T, `stride` bytes apart from `bytes` on; a digital line keeps
// only bit `bit` of each (as 0 or 1).
template <typename T>
void append_values(const unsigned char* bytes, std::size_t count, std::size_t stride,
                   bool big_endian, std::optional<int> bit, std::vector<double>& out) {
  for (std::size_t i = 0; i < count; ++i) {
    const T value = load<T>(bytes + i * stride, big_endian);
    if constexpr (std::is_integral_v<T>) {
      if (bit) {
        out.push_back(static_cast<double>((static_cast<std::uint64_t>(value) >> *bit) & 1u));
        continue;
      }
    }
    out.push_back(static_cast<double>(value));
  }
}

void append_samples(Sample sample, const unsigned char* bytes, std::size_t count,
                    std::size_t stride, bool big_endian, std::optional<int> bit,
                    std::vector<double>& out) {
  switch (sample) {
    case Sample::I8:
      return append_values<std::int8_t>(bytes, count, stride, big_endian, bit, out);
    case Sample::I16:
      return append_values<std::int16_t>(bytes, count, stride, big_endian, bit, out);
    case Sample::I32:
      return append_values<std::int32_t>(bytes, count, stride, big_endian, bit, out);
    case Sample::I64:
      return append_values<std::int64_t>(bytes, count, stride, big_endian, bit, out);
    case Sample::U8:
      return append_values<std::uint8_t>(bytes, count, stride, big_endian, bit, out);
    case Sample::U16:
      return append_values<std::uint16_t>(bytes, count, stride, big_endian, bit, out);
    case Sample::U32:
      return append_values<std::uint32_t>(bytes, count, stride, big_endian, bit, out);
    case Sample::U64:
      return append_values<std::uint64_t>(bytes, count, stride, big_endian, bit, out);
    case Sample::F32:
      return append_values<float>(bytes, count, stride, big_endian, bit, out);
    case Sample::F64:
      return append_values<double>(bytes, count, stride, big_endian, bit, out);
  }
}

// A file read at given offsets (POSIX pread: no buffering behind the reader's back).
class TdmsFile {
 public:
  explicit TdmsFile(const std::string& path) : path_(path) {
    check_data_file(path);
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw InputError(path + ": cannot open: " + std::strerror(errno));
    struct stat status {};
    if (::fstat(fd_, &status) != 0 || status.st_size < 0) {
      const int error = errno;
      ::close(fd_);
      throw InputError(path + ": cannot read: " + std::strerror(error));
    }
    size_bytes_ = static_cast<std::uint64_t>(status.st_size);
  }
  TdmsFile(const TdmsFile&) = delete;
  TdmsFile& operator=(const TdmsFile&) = delete;
  ~TdmsFile() { ::close(fd_); }

  std::uint64_t size_bytes() const { return size_bytes_; }

  void read(std::uint64_t offset, std::size_t count, unsigned char* out) const {
    std::size_t done = 0;
    while (done < count) {
      const ssize_t got = ::pread(fd_, out + done, count - done, static_cast<off_t>(offset + done));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) {
        throw InputError(path_ + ": cannot read " + std::to_string(count) + " bytes at byte " +
                         std::to_string(offset) + ": " +
                         (got < 0 ? std::strerror(errno) : "the file ended (did it change?)"));
      }
      done += static_cast<std::size_t>(got);
    }
  }

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_bytes_ = 0;
};

// One DAQmx scaler: where one of a channel's raw values lies in a raw buffer's stride.
struct DaqmxScaler {
  std::uint32_t type = 0;  // kDaqmxTypes
  std::uint32_t buffer = 0;
  std::uint32_t byte_offset = 0;  // of the value within the stride
  std::optional<int> bit;         // digital line scaler: the line's bit in that value
  std::uint32_t scale_id = 0;
};

// How an object's values lie in each chunk of a segment (its raw data index).
struct RawIndex {
  bool daqmx = false;
  std::uint32_t data_type = 0;
  std::uint64_t values = 0;      // per chunk
  std::uint64_t size_bytes = 0;  // per chunk (not DAQmx)
  std::vector<DaqmxScaler> scalers;
  std::vector<std::uint32_t> widths_bytes;  // DAQmx: the stride of each raw buffer
};

struct TdmsObject {
  std::string path;                // as in the file
  std::vector<std::string> names;  // none: the file; group; group and channel
  nlohmann::json properties = nlohmann::json::object();
  std::shared_ptr<const RawIndex> last_index;  // for "same as previous segment"
  std::optional<std::uint32_t> data_type;      // the first one with data; it may not change
  std::shared_ptr<const RawIndex> first_index;
  std::int64_t values = 0;
  int list_position = -1;  // in the current segment's object list
};

// One entry of a segment's object list.
struct ListEntry {
  std::size_t object = 0;
  bool has_data = false;
  std::shared_ptr<const RawIndex> index;
};

// One channel's values in every chunk of a segment.
struct ChunkEntry {
  std::size_t object = 0;
  const RawIndex* index = nullptr;
  std::uint64_t offset_bytes = 0;  // contiguous: its block; interleaved: within a row
  std::uint64_t stride_bytes = 0;  // between its values (not DAQmx)
};

// The raw data of one segment that holds data.
struct SegmentData {
  int number = 0;
  std::uint64_t position = 0;  // of the lead-in
  bool big_endian = false;
  bool daqmx = false;
  std::uint64_t data_position = 0;
  std::uint64_t chunk_bytes = 0;
  std::uint64_t chunks = 0;
  const std::vector<ChunkEntry>* entries = nullptr;
  const std::vector<std::uint64_t>* buffer_offsets = nullptr;  // DAQmx, within a chunk
};

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

// Splits "/'group'/'channel'" into its names ('' stands for one quote); false if malformed.
bool split_path(std::string_view path, std::vector<std::string>& names) {
  names.clear();
  if (path == "/") return true;
  std::size_t i = 0;
  while (i < path.size()) {
    if (path[i] != '/' || i + 1 >= path.size() || path[i + 1] != '\'') return false;
    i += 2;
    std::string name;
    for (;;) {
      if (i >= path.size()) return false;
      if (path[i] == '\'') {
        if (i + 1 < path.size() && path[i + 1] == '\'') {
          name += '\'';
          i += 2;
          continue;
        }
        ++i;
        break;
      }
      name += path[i++];
    }
    names.push_back(valid_utf8(name));
  }
  return !names.empty() && names.size() <= 2;
}

// Walks the segments of a TDMS file: lead-ins and metadata, seeking over the raw data. Calls
// `on_data` for each segment that holds whole chunks of data.
class TdmsParser {
 public:
  explicit TdmsParser(const std::string& path) : path_(path), file_(path) {}

  const TdmsFile& file() const { return file_; }
  const std::vector<TdmsObject>& objects() const { return objects_; }
  int segments() const { return segments_; }
  std::uint32_t version() const { return version_; }
  const std::string& truncation() const { return truncation_; }

  void run(const std::function<void(const SegmentData&)>& on_data) {
    const std::uint64_t size = file_.size_bytes();
    std::uint64_t position = 0;
    while (position < size) {
      where_ = "segment " + std::to_string(segments_) + " at byte " + std::to_string(position);
      const std::uint64_t remaining = size - position;
      unsigned char lead_in[kLeadInBytes];
      const auto lead_in_bytes = static_cast<std::size_t>(std::min(remaining, kLeadInBytes));
      file_.read(position, lead_in_bytes, lead_in);
      const std::size_t tag_bytes = std::min<std::size_t>(4, lead_in_bytes);
      if (std::memcmp(lead_in, "TDSm", tag_bytes) != 0) {
        std::string tag;
        for (std::size_t i = 0; i < tag_bytes; ++i) {
          const auto c = static_cast<char>(lead_in[i]);
          tag += (c >= 0x20 && c < 0x7F) ? std::string(1, c) : "\\x" + hex(lead_in[i]).substr(2);
        }
        fail(std::string(segments_ == 0 ? "not a TDMS file" : "not a TDMS segment") +
             ": it starts with \"" + tag + "\", not \"TDSm\"");
      }
      if (remaining < kLeadInBytes) {
        truncation_ = "the file ends " + std::to_string(remaining) +
                      " bytes into the lead-in of segment " + std::to_string(segments_) +
                      " (a file still being written?); those bytes are left out";
        break;
      }
      const std::uint32_t toc = load<std::uint32_t>(lead_in + 4, false);  // always little-endian
      const bool big_endian = (toc & kTocBigEndian) != 0;
      const auto version = load<std::uint32_t>(lead_in + 8, big_endian);
      const auto next_offset = load<std::uint64_t>(lead_in + 12, big_endian);
      const auto raw_offset = load<std::uint64_t>(lead_in + 20, big_endian);
      if (version != 4712 && version != 4713) {
        fail("unknown version " + std::to_string(version) + " (4712 and 4713 are read)");
      }
      if (segments_ == 0) version_ = version;
      const std::uint64_t after_lead_in = remaining - kLeadInBytes;
      if (raw_offset > after_lead_in) {
        fail("the raw data offset " + std::to_string(raw_offset) +
             " points beyond the end of the file (" + std::to_string(after_lead_in) +
             " bytes follow the lead-in)");
      }
      if (next_offset != kLengthUnknown && next_offset < raw_offset) {
        fail("the next segment offset " + std::to_string(next_offset) +
             " lies before the raw data offset " + std::to_string(raw_offset));
      }
      const bool truncated = next_offset == kLengthUnknown || next_offset > after_lead_in;
      const std::uint64_t end = truncated ? size : position + kLeadInBytes + next_offset;

      if ((toc & kTocMetaData) != 0) {
        read_metadata(position + kLeadInBytes, raw_offset, toc);
      }
      const std::uint64_t data_position = position + kLeadInBytes + raw_offset;
      const std::uint64_t data_bytes = (toc & kTocRawData) != 0 ? end - data_position : 0;
      std::uint64_t chunks = 0;
      if (data_bytes > 0) {
        update_layout(toc);
        if (chunk_bytes_ == 0) {
          fail("it holds " + std::to_string(data_bytes) +
               " bytes of raw data, but no channel has data in it");
        }
        chunks = data_bytes / chunk_bytes_;
        const std::uint64_t rest = data_bytes % chunk_bytes_;
        if (rest != 0 && !truncated) {
          fail("its " + std::to_string(data_bytes) + " bytes of raw data are not a whole number " +
               "of " + std::to_string(chunk_bytes_) + "-byte chunks");
        }
        if (truncated) {
          truncation_ = "segment " + std::to_string(segments_) + " is cut short (" +
                        (next_offset == kLengthUnknown
                             ? std::string("its length was never written")
                             : "it should end " + std::to_string(next_offset - after_lead_in) +
                                   " bytes after the end of the file") +
                        ", a file still being written?): its " + std::to_string(chunks) +
                        " whole chunks are read, " + std::to_string(rest) +
                        " bytes of a partial chunk are left out";
        }
      } else if (truncated) {
        truncation_ = "segment " + std::to_string(segments_) +
                      " is cut short (a file still being written?); it holds no raw data";
      }
      if (chunks > 0) {
        for (const ChunkEntry& entry : entries_) {
          // values × chunks ≤ the segment's bytes: no overflow.
          objects_[entry.object].values += static_cast<std::int64_t>(entry.index->values * chunks);
        }
        if (on_data) {
          SegmentData data;
          data.number = segments_;
          data.position = position;
          data.big_endian = big_endian;
          data.daqmx = (toc & kTocDAQmxRawData) != 0;
          data.data_position = data_position;
          data.chunk_bytes = chunk_bytes_;
          data.chunks = chunks;
          data.entries = &entries_;
          data.buffer_offsets = &buffer_offsets_;
          on_data(data);
        }
      }
      ++segments_;
      position = end;
    }
    if (segments_ == 0) throw InputError(path_ + ": not a TDMS file: the file is empty");
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_ + ": " + where_ + ": " + problem);
  }

 private:
  void read_metadata(std::uint64_t offset, std::uint64_t size_bytes, std::uint32_t toc) {
    // size_bytes ≤ the bytes after the lead-in (checked): the allocation is bounded by the file.
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size_bytes));
    file_.read(offset, bytes.size(), bytes.data());
    std::string object_where;
    MetadataCursor cursor(bytes, offset, (toc & kTocBigEndian) != 0,
                          [&](const std::string& problem) { fail(object_where + problem); });
    if ((toc & kTocNewObjList) != 0) {
      for (const ListEntry& entry : list_) objects_[entry.object].list_position = -1;
      list_.clear();
    }
    const std::uint32_t count = cursor.u32("the number of objects");
    for (std::uint32_t i = 0; i < count; ++i) {
      object_where = "object " + std::to_string(i) + ": ";
      const std::string path = cursor.string("an object path");
      object_where = "object " + std::to_string(i) + " " + in_quotes(valid_utf8(path)) + ": ";
      const std::size_t object = find_or_add(path, object_where);
      TdmsObject& target = objects_[object];
      const std::uint32_t header = cursor.u32("a raw data index");
      ListEntry entry;
      entry.object = object;
      if (header == kIndexNoData) {
        entry.has_data = false;
        entry.index = target.last_index;
      } else if (header == kIndexSameAsPrevious) {
        if (!target.last_index) {
          fail(object_where +
               "its raw data index says \"same as the previous segment\", but no earlier "
               "segment gave one");
        }
        entry.has_data = true;
        entry.index = target.last_index;
      } else {
        if (target.names.size() != 2) fail(object_where + "only channels hold raw data");
        entry.has_data = true;
        entry.index = read_index(cursor, header, object_where);
        if (target.data_type && *target.data_type != entry.index->data_type) {
          fail(object_where + "its data type changes from " + type_name(*target.data_type) +
               " to " + type_name(entry.index->data_type));
        }
        if (!target.data_type) {
          target.data_type = entry.index->data_type;
          target.first_index = entry.index;
        }
        target.last_index = entry.index;
      }
      if (target.list_position >= 0) {
        list_[static_cast<std::size_t>(target.list_position)] = entry;
      } else {
        target.list_position = static_cast<int>(list_.size());
        list_.push_back(entry);
      }
      const std::uint32_t properties = cursor.u32("the number of properties");
      for (std::uint32_t p = 0; p < properties; ++p) {
        const std::string name = valid_utf8(cursor.string("a property name"));
        const std::uint32_t type = cursor.u32("a property type");
        target.properties[name] =
            read_value(cursor, type, object_where + "property " + in_quotes(name) + ": ");
      }
    }
    layout_valid_ = false;
  }

  std::size_t find_or_add(const std::string& path, const std::string& object_where) {
    const auto found = by_path_.find(path);
    if (found != by_path_.end()) return found->second;
    TdmsObject object;
    object.path = path;
    if (!split_path(path, object.names)) {
      fail(object_where + "not an object path (/, /'group' or /'group'/'channel')");
    }
    objects_.push_back(std::move(object));
    by_path_.emplace(path, objects_.size() - 1);
    return objects_.size() - 1;
  }

  std::shared_ptr<const RawIndex> read_index(MetadataCursor& cursor, std::uint32_t header,
                                             const std::string& object_where) {
    auto index = std::make_shared<RawIndex>();
    const std::uint64_t file_size = file_.size_bytes();
    if (header == kIndexFormatChangingScaler || header == kIndexDigitalLineScaler) {
      index->daqmx = true;
      index->data_type = cursor.u32("a DAQmx data type");
      if (index->data_type != kTypeDaqmxRaw) {
        const TypeInfo* type = type_info(index->data_type);
        if (!type || !type->sample) {
          fail(object_where + "DAQmx raw data of data type " + type_name(index->data_type) +
               " is not read");
        }
      }
      const std::uint32_t dimension = cursor.u32("the array dimension");
      if (dimension != 1) {
        fail(object_where + "array dimension " + std::to_string(dimension) +
             " (only 1 is defined)");
      }
      index->values = cursor.u64("the number of values");
      if (index->values > file_size) {
        fail(object_where + "it declares " + std::to_string(index->values) +
             " values per chunk, more than the file's " + std::to_string(file_size) + " bytes");
      }
      const bool digital = header == kIndexDigitalLineScaler;
      const std::size_t scaler_bytes = digital ? 17 : 20;
      const std::uint32_t scalers = cursor.u32("the number of DAQmx scalers");
      if (scalers == 0 || scalers > cursor.remaining() / scaler_bytes) {
        fail(object_where + "it declares " + std::to_string(scalers) +
             " DAQmx scalers, which the metadata cannot hold");
      }
      for (std::uint32_t s = 0; s < scalers; ++s) {
        DaqmxScaler scaler;
        scaler.type = cursor.u32("a DAQmx scaler");
        scaler.buffer = cursor.u32("a DAQmx scaler");
        const std::uint32_t offset = cursor.u32("a DAQmx scaler");
        if (digital) {
          cursor.skip(1, "a DAQmx scaler");  // sample format bitmap
          scaler.byte_offset = offset / 8;
          scaler.bit = static_cast<int>(offset % 8);
        } else {
          cursor.skip(4, "a DAQmx scaler");  // sample format bitmap
          scaler.byte_offset = offset;
        }
        scaler.scale_id = cursor.u32("a DAQmx scaler");
        const TypeInfo* type = daqmx_type_info(scaler.type);
        if (!type) {
          fail(object_where + "DAQmx scaler " + std::to_string(s) + ": unknown data type " +
               std::to_string(scaler.type));
        }
        if (digital && (type->sample == Sample::F32 || type->sample == Sample::F64)) {
          fail(object_where + "a digital line scaler of data type " + type->name);
        }
        index->scalers.push_back(scaler);
      }
      const std::uint32_t widths = cursor.u32("the number of raw data widths");
      if (widths > cursor.remaining() / 4) {
        fail(object_where + "it declares " + std::to_string(widths) +
             " raw data widths, which the metadata cannot hold");
      }
      for (std::uint32_t w = 0; w < widths; ++w) {
        const std::uint32_t width = cursor.u32("a raw data width");
        if (width == 0) fail(object_where + "raw buffer " + std::to_string(w) + " has width 0");
        if (index->values > file_size / width) {
          fail(object_where + "raw buffer " + std::to_string(w) + " of " +
               std::to_string(index->values) + " values of " + std::to_string(width) +
               " bytes would be larger than the file");
        }
        index->widths_bytes.push_back(width);
      }
      for (std::size_t s = 0; s < index->scalers.size(); ++s) {
        const DaqmxScaler& scaler = index->scalers[s];
        if (scaler.buffer >= index->widths_bytes.size()) {
          fail(object_where + "DAQmx scaler " + std::to_string(s) + " reads raw buffer " +
               std::to_string(scaler.buffer) + ", but there are " +
               std::to_string(index->widths_bytes.size()));
        }
        const std::uint64_t end =
            std::uint64_t{scaler.byte_offset} + daqmx_type_info(scaler.type)->size_bytes;
        if (end > index->widths_bytes[scaler.buffer]) {
          fail(object_where + "DAQmx scaler " + std::to_string(s) + " reads bytes up to " +
               std::to_string(end) + " of a " + std::to_string(index->widths_bytes[scaler.buffer]) +
               "-byte stride");
        }
      }
      return index;
    }
    // A plain raw data index; `header` is its length in bytes, itself included.
    const std::size_t start = cursor.position() - 4;
    if (header < 20) {
      fail(object_where + "raw data index length " + std::to_string(header) +
           " (20, or 28 for strings)");
    }
    if (header - 4 > cursor.remaining()) {
      fail(object_where + "its raw data index of " + std::to_string(header) +
           " bytes points beyond the end of the metadata");
    }
    index->data_type = cursor.u32("a data type");
    const TypeInfo* type = type_info(index->data_type);
    if (!type) fail(object_where + "unknown data type " + hex(index->data_type));
    const std::uint32_t dimension = cursor.u32("the array dimension");
    if (dimension != 1) {
      fail(object_where + "array dimension " + std::to_string(dimension) + " (only 1 is defined)");
    }
    index->values = cursor.u64("the number of values");
    if (index->data_type == kTypeString) {
      if (header < 28) {
        fail(object_where + "a raw data index of strings needs 28 bytes, not " +
             std::to_string(header));
      }
      index->size_bytes = cursor.u64("the size of the strings");
      // Each string has a 4-byte end offset before the text.
      if (index->size_bytes > file_size || index->values > index->size_bytes / 4) {
        fail(object_where + "strings of " + std::to_string(index->size_bytes) + " bytes for " +
             std::to_string(index->values) + " values do not fit the file");
      }
    } else {
      if (type->size_bytes == 0) {
        fail(object_where + "data type " + type_name(index->data_type) +
             " is not read (its size in the raw data is not documented)");
      }
      if (index->values > file_size / type->size_bytes) {
        fail(object_where + "it declares " + std::to_string(index->values) + " values of " +
             type->name + " per chunk, more than the file holds");
      }
      index->size_bytes = index->values * type->size_bytes;
    }
    cursor.skip(start + header - cursor.position(), "the raw data index");
    return index;
  }

  nlohmann::json read_value(MetadataCursor& cursor, std::uint32_t type,
                            const std::string& property_where) {
    switch (type) {
      case 0x01:
        return cursor.number<std::int8_t>("a property value");
      case 0x02:
        return cursor.number<std::int16_t>("a property value");
      case 0x03:
        return cursor.number<std::int32_t>("a property value");
      case 0x04:
        return cursor.number<std::int64_t>("a property value");
      case 0x05:
        return cursor.number<std::uint8_t>("a property value");
      case 0x06:
        return cursor.number<std::uint16_t>("a property value");
      case 0x07:
        return cursor.number<std::uint32_t>("a property value");
      case 0x08:
        return cursor.number<std::uint64_t>("a property value");
      case 0x09:
      case 0x19:
        return cursor.number<float>("a property value");
      case 0x0A:
      case 0x1A:
        return cursor.number<double>("a property value");
      case kTypeString:
        return valid_utf8(cursor.string("a property value"));
      case kTypeBoolean:
        return cursor.number<std::uint8_t>("a property value") != 0;
      case kTypeTimestamp: {
        // Little-endian: fractions, then seconds; big-endian: seconds, then fractions.
        std::uint64_t fraction = 0;
        std::int64_t seconds = 0;
        if (cursor.big_endian()) {
          seconds = cursor.number<std::int64_t>("a timestamp");
          fraction = cursor.number<std::uint64_t>("a timestamp");
        } else {
          fraction = cursor.number<std::uint64_t>("a timestamp");
          seconds = cursor.number<std::int64_t>("a timestamp");
        }
        return timestamp_text(seconds, fraction);
      }
      case kTypeComplex64: {
        const float re = cursor.number<float>("a property value");
        const float im = cursor.number<float>("a property value");
        return nlohmann::json::array({re, im});
      }
      case kTypeComplex128: {
        const double re = cursor.number<double>("a property value");
        const double im = cursor.number<double>("a property value");
        return nlohmann::json::array({re, im});
      }
      default:
        fail(property_where + "data type " + type_name(type) + " is not read");
    }
  }

  // The layout of a chunk for the current object list (recomputed when the metadata or the
  // kind of segment changes).
  void update_layout(std::uint32_t toc) {
    const std::uint32_t kind = toc & (kTocInterleavedData | kTocDAQmxRawData);
    if (layout_valid_ && kind == layout_kind_) return;
    entries_.clear();
    buffer_offsets_.clear();
    chunk_bytes_ = 0;
    const std::uint64_t file_size = file_.size_bytes();
    auto add_bytes = [&](std::uint64_t bytes) {
      // Both ≤ the file size, so the sum cannot overflow.
      chunk_bytes_ += bytes;
      if (chunk_bytes_ > file_size) {
        fail("its chunks of " + std::to_string(chunk_bytes_) +
             " bytes or more are larger than the file");
      }
    };
    std::vector<std::uint64_t> buffer_values;
    for (const ListEntry& item : list_) {
      if (!item.has_data || item.index->values == 0) continue;
      const RawIndex& index = *item.index;
      const TdmsObject& object = objects_[item.object];
      const std::string object_where = "channel " + in_quotes(valid_utf8(object.path)) + ": ";
      if ((toc & kTocDAQmxRawData) != 0) {
        if (!index.daqmx) fail(object_where + "a plain raw data index in a DAQmx segment");
        if (entries_.empty()) {
          buffer_values.assign(index.widths_bytes.size(), 0);
        } else if (index.widths_bytes != entries_.front().index->widths_bytes) {
          fail(object_where + "its raw data widths differ from those of the other channels");
        }
        for (const DaqmxScaler& scaler : index.scalers) {
          std::uint64_t& values = buffer_values[scaler.buffer];
          if (values != 0 && values != index.values) {
            fail(object_where + "raw buffer " + std::to_string(scaler.buffer) + " holds " +
                 std::to_string(values) + " values per chunk for one channel and " +
                 std::to_string(index.values) + " for another");
          }
          values = index.values;
        }
      } else {
        if (index.daqmx) {
          fail(object_where + "a DAQmx raw data index in a segment without DAQmx raw data");
        }
        if ((toc & kTocInterleavedData) != 0) {
          if (index.data_type == kTypeString) fail(object_where + "interleaved strings");
          if (!entries_.empty() && entries_.front().index->values != index.values) {
            fail(object_where + "interleaved with " + std::to_string(index.values) +
                 " values per chunk, another channel has " +
                 std::to_string(entries_.front().index->values));
          }
        }
      }
      entries_.push_back(ChunkEntry{item.object, item.index.get(), 0, 0});
    }
    if ((toc & kTocDAQmxRawData) != 0) {
      if (!entries_.empty()) {
        const std::vector<std::uint32_t>& widths = entries_.front().index->widths_bytes;
        for (std::size_t b = 0; b < widths.size(); ++b) {
          buffer_offsets_.push_back(chunk_bytes_);
          add_bytes(buffer_values[b] * widths[b]);  // checked against the file size on reading
        }
      }
    } else if ((toc & kTocInterleavedData) != 0) {
      std::uint64_t row_bytes = 0;
      for (ChunkEntry& entry : entries_) {
        entry.offset_bytes = row_bytes;
        row_bytes += type_info(entry.index->data_type)->size_bytes;
      }
      for (ChunkEntry& entry : entries_) entry.stride_bytes = row_bytes;
      if (!entries_.empty()) {
        if (entries_.front().index->values > file_size / row_bytes) {
          fail("its interleaved rows of " + std::to_string(row_bytes) + " bytes are more than " +
               "the file holds");
        }
        add_bytes(entries_.front().index->values * row_bytes);
      }
    } else {
      for (ChunkEntry& entry : entries_) {
        entry.offset_bytes = chunk_bytes_;
        entry.stride_bytes = type_info(entry.index->data_type)->size_bytes;
        add_bytes(entry.index->size_bytes);
      }
    }
    layout_valid_ = true;
    layout_kind_ = kind;
  }

  std::string path_;
  TdmsFile file_;
  std::vector<TdmsObject> objects_;
  std::unordered_map<std::string, std::size_t> by_path_;
  std::vector<ListEntry> list_;
  std::vector<ChunkEntry> entries_;
  std::vector<std::uint64_t> buffer_offsets_;
  std::uint64_t chunk_bytes_ = 0;
  bool layout_valid_ = false;
  std::uint32_t layout_kind_ = 0;
  int segments_ = 0;
  std::uint32_t version_ = 0;
  std::string where_;
  std::string truncation_;
};

// "group/channel": the names as in the file, joined by '/'.
std::string signal_name(const TdmsObject& object) {
  return object.names[0] + "/" + object.names[1];
}

std::optional<double> number_property(const nlohmann::json& properties, const std::string& name) {
  const auto found = properties.find(name);
  if (found == properties.end() || !found->is_number()) return std::nullopt;
  return found->get<double>();
}

std::string stored_type(const TdmsObject& object) {
  if (!object.first_index) return "none";
  const RawIndex& index = *object.first_index;
  if (!index.daqmx) return type_info(index.data_type)->name;
  const DaqmxScaler& scaler = index.scalers.front();
  std::string text = std::string(daqmx_type_info(scaler.type)->name) +
                     (scaler.bit ? " (DAQmx digital line" : " (DAQmx raw data");
  if (index.scalers.size() > 1) text += ", " + std::to_string(index.scalers.size()) + " scalers";
  return text + ")";
}

// The format's own scaling of a channel (its NI_Scale[n] properties): the DAQmx scaler its
// values start from (none: the channel's only scaler, or its stored values), then each linear
// step in order.
struct ScalePlan {
  std::optional<std::uint32_t> scale_id;
  std::vector<std::pair<double, double>> steps;  // value → slope × value + intercept
};

ScalePlan scale_plan(const TdmsObject& object, const std::string& path) {
  const nlohmann::json& properties = object.properties;
  const std::string where = path + ": " + in_quotes(signal_name(object)) + ": ";
  ScalePlan plan;
  const auto status = properties.find("NI_Scaling_Status");
  if (status != properties.end() && status->is_string() && *status == "scaled") return plan;
  const std::optional<double> count = number_property(properties, "NI_Number_Of_Scales");
  if (!count || *count == 0) return plan;
  if (!(*count >= 1 && *count <= 4294967295.0) || *count != std::floor(*count)) {
    throw InputError(where + "NI_Number_Of_Scales is " + number_text(*count));
  }
  auto scale = static_cast<std::uint32_t>(*count - 1);
  std::vector<std::pair<double, double>> from_last;
  for (;;) {
    const std::string prefix = "NI_Scale[" + std::to_string(scale) + "]_";
    const auto type = properties.find(prefix + "Scale_Type");
    if (type == properties.end()) {
      // A scale the properties do not describe: the values of the DAQmx scaler of that ID.
      if (object.first_index && object.first_index->daqmx) plan.scale_id = scale;
      break;
    }
    if (!type->is_string() || *type != "Linear") {
      throw InputError(where + prefix + "Scale_Type is " + type->dump().substr(0, 60) +
                       ": only Linear scales are read");
    }
    const std::optional<double> slope = number_property(properties, prefix + "Linear_Slope");
    const std::optional<double> intercept =
        number_property(properties, prefix + "Linear_Y_Intercept");
    if (!slope || !intercept) {
      throw InputError(where + prefix + "Scale_Type is \"Linear\", but " + prefix +
                       "Linear_Slope or " + prefix + "Linear_Y_Intercept is missing");
    }
    from_last.emplace_back(*slope, *intercept);
    const std::optional<double> source =
        number_property(properties, prefix + "Linear_Input_Source");
    if (!source || *source == kScaleInputRaw) break;
    if (!(*source >= 0 && *source < scale) || *source != std::floor(*source)) {
      throw InputError(where + prefix + "Linear_Input_Source " + number_text(*source) +
                       " is not an earlier scale");
    }
    scale = static_cast<std::uint32_t>(*source);
  }
  plan.steps.assign(from_last.rbegin(), from_last.rend());
  return plan;
}

// Reads `count` values `stride_bytes` apart from byte `start` on, in blocks of at most
// kReadBlockBytes.
void read_strided(const TdmsFile& file, std::uint64_t start, std::uint64_t count,
                  std::uint64_t stride_bytes, std::uint64_t size_bytes, Sample sample,
                  bool big_endian, std::optional<int> bit, std::vector<unsigned char>& buffer,
                  std::vector<double>& out) {
  const std::uint64_t per_block = std::max<std::uint64_t>(1, kReadBlockBytes / stride_bytes);
  std::uint64_t done = 0;
  while (done < count) {
    const std::uint64_t n = std::min(per_block, count - done);
    const std::uint64_t bytes = (n - 1) * stride_bytes + size_bytes;
    buffer.resize(static_cast<std::size_t>(bytes));
    file.read(start + done * stride_bytes, buffer.size(), buffer.data());
    append_samples(sample, buffer.data(), static_cast<std::size_t>(n),
                   static_cast<std::size_t>(stride_bytes), big_endian, bit, out);
    done += n;
  }
}

class TdmsFormat final : public SignalFileReader {
 public:
  std::string_view format_name() const override { return "NI TDMS"; }
  bool matches_signature(std::string_view head) const override {
    return head.substr(0, 4) == "TDSm";
  }
  bool matches_extension(std::string_view extension) const override { return extension == ".tdms"; }

  FileContents describe(const std::string& path) const override {
    TdmsParser parser(path);
    parser.run(nullptr);
    FileContents contents;
    contents.container = "NI TDMS (version " + std::to_string(parser.version()) + "), " +
                         std::to_string(parser.segments()) +
                         (parser.segments() == 1 ? " segment" : " segments");
    if (!parser.truncation().empty()) contents.container += "; " + parser.truncation();
    contents.properties["file"] = nlohmann::json::object();
    contents.properties["groups"] = nlohmann::json::object();
    if (!parser.truncation().empty()) contents.properties["truncation"] = parser.truncation();
    for (const TdmsObject& object : parser.objects()) {
      if (object.names.empty()) {
        contents.properties["file"] = object.properties;
      } else if (object.names.size() == 1) {
        contents.properties["groups"][object.names[0]] = object.properties;
      } else {
        FileSignal signal;
        signal.name = signal_name(object);
        signal.sample_count = object.values;
        const auto unit = object.properties.find("unit_string");
        if (unit != object.properties.end() && unit->is_string()) {
          signal.unit = unit->get<std::string>();
        }
        const std::optional<double> increment_s =
            number_property(object.properties, "wf_increment");
        if (increment_s && std::isfinite(*increment_s) && *increment_s > 0.0 &&
            std::isfinite(1.0 / *increment_s)) {
          signal.sample_rate_hz = 1.0 / *increment_s;
        }
        signal.stored_type = stored_type(object);
        signal.properties = object.properties;
        contents.file_signals.push_back(std::move(signal));
      }
    }
    return contents;
  }

  std::vector<double> read_signal(const std::string& path, const FileSignal& signal,
                                  int column) const override {
    TdmsParser layout(path);
    layout.run(nullptr);
    const std::vector<TdmsObject>& objects = layout.objects();
    std::optional<std::size_t> found;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (objects[i].names.size() != 2 || signal_name(objects[i]) != signal.name) continue;
      if (found) {
        throw InputError(path + ": two channels are named " + in_quotes(signal.name) + " (" +
                         in_quotes(objects[*found].path) + " and " + in_quotes(objects[i].path) +
                         ")");
      }
      found = i;
    }
    if (!found) {
      throw InputError(path + ": the file holds no channel " + in_quotes(signal.name));
    }
    if (column > 0) {
      throw InputError(path + ": " + in_quotes(signal.name) + " has one column, not " +
                       std::to_string(column + 1));
    }
    const TdmsObject& object = objects[*found];
    if (!object.first_index) return {};
    if (!object.first_index->daqmx && !type_info(object.first_index->data_type)->sample) {
      throw InputError(path + ": " + in_quotes(signal.name) + " stores " +
                       type_info(object.first_index->data_type)->name +
                       " values, which are not samples (int8 to uint64, float32 and float64 "
                       "are read)");
    }
    const ScalePlan plan = scale_plan(object, path);

    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(object.values));  // ≤ the file's raw data bytes
    std::vector<unsigned char> buffer;
    TdmsParser data(path);
    data.run([&](const SegmentData& segment) {
      const auto entry = std::find_if(segment.entries->begin(), segment.entries->end(),
                                      [&](const ChunkEntry& e) { return e.object == *found; });
      if (entry == segment.entries->end()) return;
      const RawIndex& index = *entry->index;
      Sample sample = Sample::F64;
      std::uint64_t first_bytes = 0;
      std::uint64_t stride_bytes = 0;
      std::uint64_t size_bytes = 0;
      std::optional<int> bit;
      if (index.daqmx) {
        const DaqmxScaler* scaler = nullptr;
        for (const DaqmxScaler& candidate : index.scalers) {
          if (plan.scale_id ? candidate.scale_id == *plan.scale_id : index.scalers.size() == 1) {
            scaler = &candidate;
            break;
          }
        }
        if (!scaler) {
          data.fail(in_quotes(signal.name) + ": " +
                    (plan.scale_id
                         ? "no DAQmx scaler has scale ID " + std::to_string(*plan.scale_id)
                         : std::to_string(index.scalers.size()) +
                               " DAQmx scalers and no NI_Scale property picks one"));
        }
        const TypeInfo* type = daqmx_type_info(scaler->type);
        sample = *type->sample;
        size_bytes = type->size_bytes;
        first_bytes = (*segment.buffer_offsets)[scaler->buffer] + scaler->byte_offset;
        stride_bytes = index.widths_bytes[scaler->buffer];
        bit = scaler->bit;
      } else {
        const TypeInfo* type = type_info(index.data_type);
        sample = *type->sample;
        size_bytes = type->size_bytes;
        first_bytes = entry->offset_bytes;
        stride_bytes = entry->stride_bytes;
      }
      for (std::uint64_t chunk = 0; chunk < segment.chunks; ++chunk) {
        read_strided(data.file(), segment.data_position + chunk * segment.chunk_bytes + first_bytes,
                     index.values, stride_bytes, size_bytes, sample, segment.big_endian, bit,
                     buffer, values);
      }
    });
    for (const auto& [slope, intercept] : plan.steps) {
      for (double& value : values) value = slope * value + intercept;
    }
    return values;
  }
};

}  // namespace

const FormatReader& tdms_format() {
  static const TdmsFormat format;
  return format;
}

}  // namespace oscilab::daq

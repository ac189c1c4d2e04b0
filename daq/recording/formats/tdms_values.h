#pragma once

// The data types of TDMS raw data and the reading of stored values: byte order, strides, DAQmx
// digital lines, and the file they are read from at given offsets.
#include <bit>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace oscilab::daq::tdms {

inline constexpr std::uint32_t kTypeString = 0x20;
inline constexpr std::uint32_t kTypeBoolean = 0x21;
inline constexpr std::uint32_t kTypeTimestamp = 0x44;
inline constexpr std::uint32_t kTypeComplex64 = 0x08000C;
inline constexpr std::uint32_t kTypeComplex128 = 0x10000D;
inline constexpr std::uint32_t kTypeDaqmxRaw = 0xFFFFFFFF;

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

/// The tdsDataType of `code`, or nullptr when it is none.
const TypeInfo* type_info(std::uint32_t code);
/// The data type of a DAQmx scaler (an enumeration of its own), or nullptr when it is none.
const TypeInfo* daqmx_type_info(std::uint32_t code);
/// "float64 (0xA)", or "unknown (0x...)", for messages.
std::string type_name(std::uint32_t code);
/// `value` in hexadecimal: "0x1F".
std::string hex(std::uint64_t value);

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

// A file read at given offsets (POSIX pread: no buffering behind the reader's back).
class TdmsFile {
 public:
  /// Opens `path`; throws InputError when it is not a readable regular file.
  explicit TdmsFile(const std::string& path);
  TdmsFile(const TdmsFile&) = delete;
  TdmsFile& operator=(const TdmsFile&) = delete;
  ~TdmsFile();

  std::uint64_t size_bytes() const { return size_bytes_; }

  /// Reads `count` bytes at `offset` into `out`; throws InputError when the file holds fewer.
  void read(std::uint64_t offset, std::size_t count, unsigned char* out) const;

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_bytes_ = 0;
};

// Reads `count` values of `sample` (`size_bytes` each) `stride_bytes` apart from byte `start` on
// and appends them to `out`, in blocks of at most 1 MiB through `buffer`; a digital line keeps
// only bit `bit` of each (as 0 or 1).
void read_strided(const TdmsFile& file, std::uint64_t start, std::uint64_t count,
                  std::uint64_t stride_bytes, std::uint64_t size_bytes, Sample sample,
                  bool big_endian, std::optional<int> bit, std::vector<unsigned char>& buffer,
                  std::vector<double>& out);

}  // namespace oscilab::daq::tdms

#include "daq/recording/formats/tdms_values.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>

#include "analysis/common/input_error.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq::tdms {
namespace {

constexpr std::size_t kReadBlockBytes = std::size_t{1} << 20;  // at most this read at once

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

}  // namespace

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

TdmsFile::TdmsFile(const std::string& path) : path_(path) {
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

TdmsFile::~TdmsFile() { ::close(fd_); }

void TdmsFile::read(std::uint64_t offset, std::size_t count, unsigned char* out) const {
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

}  // namespace oscilab::daq::tdms

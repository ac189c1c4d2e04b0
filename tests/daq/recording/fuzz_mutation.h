#pragma once

// The byte mutations the readers' fuzz tests share: truncation at any byte, bit flips, random or
// chosen bytes, copied ranges, and numeric fields set to extreme values. Each draws from the
// test's seeded generator in a fixed order, so a test's seed and iteration reproduce its file.
// A test composes them into its own mutation; format-specific cases stay in the test.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <string_view>

namespace oscilab::daq::testing {

/// A position in [0, size], uniform.
inline std::size_t random_position(std::size_t size, std::mt19937_64& rng) {
  return std::uniform_int_distribution<std::size_t>(0, size)(rng);
}

/// Truncation at any byte, the empty file and the whole one included.
inline void truncate_anywhere(std::string& bytes, std::mt19937_64& rng) {
  bytes.resize(random_position(bytes.size(), rng));
}

/// Flips one random bit of a random byte, `count` times (none in an empty file).
inline void flip_bits(std::string& bytes, int count, std::mt19937_64& rng) {
  for (int i = 0; i < count && !bytes.empty(); ++i) {
    const auto bit = static_cast<char>(1 << (rng() % 8));
    bytes[random_position(bytes.size() - 1, rng)] ^= bit;
  }
}

/// Overwrites a random byte, `count` times (none in an empty file), with a random byte or, half
/// of the time when `alphabet` is given, with one of its characters.
inline void overwrite_bytes(std::string& bytes, int count, std::mt19937_64& rng,
                            std::string_view alphabet = {}) {
  for (int i = 0; i < count && !bytes.empty(); ++i) {
    const bool from_alphabet = !alphabet.empty() && rng() % 2 == 0;
    const char value =
        from_alphabet ? alphabet[rng() % alphabet.size()] : static_cast<char>(rng() & 0xff);
    bytes[random_position(bytes.size() - 1, rng)] = value;
  }
}

/// `length` random bytes, to insert.
inline std::string random_bytes(std::size_t length, std::mt19937_64& rng) {
  std::string bytes(length, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  return bytes;
}

/// Inserts a copy of the `length` bytes from `from` on (fewer at the end) at a random position:
/// a repeated segment, record or field.
inline void repeat_range(std::string& bytes, std::size_t from, std::size_t length,
                         std::mt19937_64& rng) {
  const std::string copy = bytes.substr(from, length);
  bytes.insert(random_position(bytes.size(), rng), copy);
}

/// A value a numeric field is set to: its low `width` bytes.
struct FieldValue {
  std::uint64_t value;
  std::size_t width;
};

/// The bits of a float64, to set a field to it.
inline std::uint64_t bits_of(double value) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

/// The bits of a float32, to set a field to it.
inline std::uint32_t bits_of(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

/// Writes the low `width` bytes of `value` at `position` in the given byte order; bytes past
/// the end of the file are left out.
inline void put_field(std::string& bytes, std::size_t position, std::uint64_t value,
                      std::size_t width, bool big_endian) {
  for (std::size_t i = 0; i < width && position + i < bytes.size(); ++i) {
    const std::size_t shift = 8 * (big_endian ? width - 1 - i : i);
    bytes[position + i] = static_cast<char>((value >> shift) & 0xff);
  }
}

}  // namespace oscilab::daq::testing

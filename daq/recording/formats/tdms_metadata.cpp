#include "daq/recording/formats/tdms_metadata.h"

#include <cstdio>

namespace oscilab::daq::tdms {

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

std::optional<nlohmann::json> read_property_value(MetadataCursor& cursor, std::uint32_t type) {
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
      return std::nullopt;
  }
}

}  // namespace oscilab::daq::tdms

#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "analysis/common/input_error.h"

namespace oscilab {

/// Limits on every JSON text Oscilab parses (sidecars, sessions, models, network HELLO and EVENT
/// frames, Python arguments). nlohmann::json copies, compares and prints a value recursively, so
/// a value nested 100 000 deep overflows the stack however few bytes it takes: the nesting is
/// counted before the text is parsed. Oscilab's own documents nest at most 5 levels (a sidecar's
/// excitation.levels[i]); 64 leaves room for whatever a user keeps under an unknown key.
inline constexpr std::size_t kMaxJsonDepth = 64;  // nested arrays and objects
/// The largest JSON text parsed: a sidecar or a session is kilobytes, a model less; 64 MiB bounds
/// the parsed value's memory (about 10× the text) to well under a gigabyte.
inline constexpr std::size_t kMaxJsonTextBytes = 64u << 20;  // bytes

/// Why `text` may not be parsed (empty when it may): longer than `max_bytes`, or arrays and
/// objects nested deeper than `max_depth` (brackets inside strings do not count). Linear in the
/// text, no allocation but the message.
inline std::string json_limit_violation(std::string_view text,
                                        std::size_t max_depth = kMaxJsonDepth,
                                        std::size_t max_bytes = kMaxJsonTextBytes);

/// Parses `text` after checking it against the limits above. Every problem throws one
/// InputError starting with `where` (a file name, "HELLO frame"): the limit exceeded, or the
/// parser's reason with its line and column.
inline nlohmann::json parse_json_within_limits(std::string_view text, const std::string& where);

// Header-only: the reader modules (daq/hdf5_module) use it without linking oscilab_analysis.

inline std::string json_limit_violation(std::string_view text, std::size_t max_depth,
                                        std::size_t max_bytes) {
  if (text.size() > max_bytes) {
    return std::to_string(text.size()) + " bytes of JSON exceed the limit of " +
           std::to_string(max_bytes);
  }
  std::size_t depth = 0;
  bool in_string = false;
  bool escaped = false;
  for (std::size_t at = 0; at < text.size(); ++at) {
    const char c = text[at];
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) {
        return "JSON nested deeper than " + std::to_string(max_depth) + " levels (at byte " +
               std::to_string(at) + ")";
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;  // unbalanced brackets are the parser's to report
    }
  }
  return "";
}

inline nlohmann::json parse_json_within_limits(std::string_view text, const std::string& where) {
  if (const std::string violation = json_limit_violation(text); !violation.empty()) {
    throw InputError(where + ": " + violation);
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& parse_error) {
    std::string reason = parse_error.what();
    // Drop nlohmann's "[json.exception.parse_error.101] " tag; keep its line and column.
    if (const auto end = reason.find("] ");
        reason.rfind("[json.exception", 0) == 0 && end != std::string::npos) {
      reason = reason.substr(end + 2);
    }
    throw InputError(where + ": malformed JSON: " + reason);
  }
}

}  // namespace oscilab

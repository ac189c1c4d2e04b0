#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace oscilab::daq {

/// Reads and parses a JSON file (a sidecar, a session). Every problem throws one InputError
/// naming the file: not found, not a regular file, larger than `max_bytes` (read nothing then),
/// unreadable, or malformed JSON with its line and column.
nlohmann::json read_json_file(const std::string& path, std::uintmax_t max_bytes);

/// Writes `text` to `path` through a temporary file beside it, handed to the disk (fdatasync),
/// and a rename (TemporaryFile), so that the target is either the old file or the complete new
/// one, after a crash or a power cut. Throws InputError.
void write_text_file_atomically(const std::string& text, const std::string& path);

}  // namespace oscilab::daq

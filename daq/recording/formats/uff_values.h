#pragma once

// The values of a time response (record 12 of dataset 58): ASCII E fields or binary IEEE 754.
#include <string>
#include <vector>

#include "daq/recording/format_reader.h"

namespace oscilab::daq::uff {

/// The `signal.sample_count` values in `text`, the ASCII record 12 of the dataset the signal's
/// properties name; `first_line` is the file line `text` starts at (0: unknown), for messages.
/// Throws InputError naming `path` when a value is not a number or the count differs.
std::vector<double> read_ascii_values(const std::string& path, const FileSignal& signal,
                                      const std::string& text, long first_line);

/// The IEEE 754 values in `bytes`, float32 or float64, in the given byte order.
std::vector<double> decode_binary_values(const std::string& bytes, bool float32, bool big_endian);

}  // namespace oscilab::daq::uff

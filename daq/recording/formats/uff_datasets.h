#pragma once

// The datasets of a universal file and the header records of dataset 58 (records 1-11, see
// uff_format.cpp): where each time response lies and what its header says, and which other
// datasets the file holds.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace oscilab::daq::uff {

// Records 8-11 of dataset 58.
struct Axis {
  long long specific_data_type = 0;
  long long length_exponent = 0;
  long long force_exponent = 0;
  long long temperature_exponent = 0;
  std::string label;
  std::string units;

  nlohmann::json to_json() const {
    return {{"specific_data_type", specific_data_type},
            {"length_unit_exponent", length_exponent},
            {"force_unit_exponent", force_exponent},
            {"temperature_unit_exponent", temperature_exponent},
            {"label", label},
            {"units", units}};
  }
};

struct Dof {
  std::string entity;
  long long node = 0;
  long long direction = 0;
};

// Records 1-11 of one dataset 58 and where its values lie.
struct Dataset58 {
  int index = 0;  // 1-based position among all datasets of the file
  std::array<std::string, 5> id_lines;
  long long function_type = 0;
  long long function_id = 0;
  long long version = 0;
  long long load_case = 0;
  Dof response;
  Dof reference;
  long long ordinate_type = 0;
  long long count = 0;
  long long spacing = 0;
  double abscissa_min = 0.0;
  double abscissa_increment = 0.0;
  std::string_view::size_type increment_decimals = 0;  // digits after the point, as printed
  long long increment_exponent = 0;                    // its decimal exponent, as printed
  double z_value = 0.0;
  std::array<Axis, 4> axes;  // abscissa, ordinate, ordinate denominator, z axis
  bool binary = false;
  int byte_order = 1;  // 1 little-endian, 2 big-endian
  std::uint64_t data_offset = 0;
  std::uint64_t data_bytes = 0;
  long data_line = 0;  // first line of the ASCII values, 0 when unknown
};

// Everything describe finds, before naming.
struct Scan {
  std::vector<Dataset58> time_responses;
  nlohmann::json skipped = nlohmann::json::array();
  int datasets = 0;
  bool any_ascii = false;
  bool any_binary = false;
  std::string byte_orders;
};

/// Reads the datasets of the universal file at `path`: the header records and the place of the
/// values of each time response, the reason each other dataset is skipped. Throws InputError
/// when the file is not a sequence of datasets or a time response cannot be read.
Scan scan_datasets(const std::string& path);

/// The function type of record 6 Field 1 by name, as the dataset 58 description lists them.
std::string function_type_name(long long type);

/// Record 8 Field 6: the time unit of the abscissa (minimum and increment) in s, nothing when the
/// units are not a time unit. "NONE" or blank: s; s, sec, secs, second(s) and ms, msec(s),
/// millisecond(s) in any case, also in parentheses or brackets ("(Sec)", "[s]").
std::optional<double> time_unit_s(std::string_view units);

}  // namespace oscilab::daq::uff

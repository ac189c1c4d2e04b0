// FileContents as JSON text and back: see contents_text.h.
#include "daq/recording/formats/contents_text.h"

#include <cstdint>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"

namespace oscilab::daq {

std::string contents_to_text(const FileContents& contents) {
  nlohmann::json json;
  json["container"] = contents.container;
  json["properties"] = contents.properties;
  json["signals"] = nlohmann::json::array();
  for (const FileSignal& signal : contents.file_signals) {
    nlohmann::json item;
    item["name"] = signal.name;
    item["sample_count"] = signal.sample_count;
    item["columns"] = signal.columns;
    item["unit"] = signal.unit;
    item["sample_rate_hz"] =
        signal.sample_rate_hz ? nlohmann::json(*signal.sample_rate_hz) : nlohmann::json(nullptr);
    item["stored_type"] = signal.stored_type;
    item["properties"] = signal.properties;
    json["signals"].push_back(std::move(item));
  }
  // Names and attributes come from the file: invalid UTF-8 is replaced, never thrown.
  return json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

FileContents contents_from_text(const std::string& text, const std::string& path) {
  const auto bad = [&] {
    return InputError(path + ": the reading process replied an unreadable description");
  };
  // The description holds the file's own attributes: their nesting is bounded like any JSON's
  // (its size is the reading process's, bounded there).
  if (!json_limit_violation(text, kMaxJsonDepth, text.size()).empty()) throw bad();
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
  if (json.is_discarded() || !json.is_object()) throw bad();
  FileContents contents;
  try {
    contents.container = json.at("container").get<std::string>();
    contents.properties = json.at("properties");
    for (const nlohmann::json& item : json.at("signals")) {
      FileSignal signal;
      signal.name = item.at("name").get<std::string>();
      signal.sample_count = item.at("sample_count").get<std::int64_t>();
      signal.columns = item.at("columns").get<std::int64_t>();
      signal.unit = item.at("unit").get<std::string>();
      if (item.at("sample_rate_hz").is_number()) {
        signal.sample_rate_hz = item.at("sample_rate_hz").get<double>();
      }
      signal.stored_type = item.at("stored_type").get<std::string>();
      signal.properties = item.at("properties");
      contents.file_signals.push_back(std::move(signal));
    }
  } catch (const nlohmann::json::exception&) {
    throw bad();
  }
  return contents;
}

}  // namespace oscilab::daq

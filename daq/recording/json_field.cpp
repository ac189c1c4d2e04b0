#include "daq/recording/json_field.h"

#include <cmath>

#include "analysis/common/input_error.h"

namespace oscilab::daq {

using nlohmann::json;

std::string json_excerpt(const json& value) {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) {
    return "a number out of range";
  }
  std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  constexpr std::size_t kMaxShown = 60;  // characters
  if (text.size() > kMaxShown) text = text.substr(0, kMaxShown) + "...";
  return text;
}

JsonField JsonField::operator/(const std::string& key) const {
  return JsonField(file_, path_.empty() ? key : path_ + "." + key);
}

JsonField JsonField::operator[](std::size_t index) const {
  return JsonField(file_, path_ + "[" + std::to_string(index) + "]");
}

std::string JsonField::where() const {
  if (file_.empty()) return path_;
  return path_.empty() ? file_ : file_ + ": " + path_;
}

void JsonField::fail(const std::string& problem) const {
  throw InputError((file_.empty() ? "" : file_ + ": ") + (path_.empty() ? "" : path_ + ": ") +
                   problem);
}

const json& JsonField::object(const json& value) const {
  if (!value.is_object()) fail("expected an object, got " + json_excerpt(value));
  return value;
}

const json& JsonField::array(const json& value) const {
  if (!value.is_array()) fail("expected an array, got " + json_excerpt(value));
  return value;
}

std::string JsonField::string(const json& value) const {
  if (!value.is_string()) fail("expected a string, got " + json_excerpt(value));
  return value.get<std::string>();
}

bool JsonField::boolean(const json& value) const {
  if (!value.is_boolean()) fail("expected true or false, got " + json_excerpt(value));
  return value.get<bool>();
}

double JsonField::number(const json& value) const {
  if (!value.is_number()) fail("expected a number, got " + json_excerpt(value));
  return value.get<double>();
}

double JsonField::finite_number(const json& value) const {
  const double x = number(value);
  if (!std::isfinite(x)) fail("expected a finite number, got " + json_excerpt(value));
  return x;
}

double JsonField::positive_number(const json& value) const {
  const double x = finite_number(value);
  if (!(x > 0.0)) fail("expected a positive number, got " + json_excerpt(value));
  return x;
}

long JsonField::integer(const json& value, long min) const {
  if (!value.is_number_integer()) fail("expected an integer, got " + json_excerpt(value));
  const long x = value.get<long>();
  if (x < min) {
    fail("expected an integer \u2265 " + std::to_string(min) + ", got " + json_excerpt(value));
  }
  return x;
}

int JsonField::whole_number(const json& value, std::int64_t max) const {
  if (!value.is_number_integer()) fail("expected a whole number, got " + json_excerpt(value));
  const bool negative = value.is_number_unsigned() ? false : value.get<std::int64_t>() < 0;
  if (negative || value.get<std::uint64_t>() > static_cast<std::uint64_t>(max)) {
    fail("expected a whole number from 0 to " + std::to_string(max) + ", got " +
         json_excerpt(value));
  }
  return static_cast<int>(value.get<std::int64_t>());
}

const json* JsonField::find(const json& object, const std::string& key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const json& JsonField::require(const json& object, const std::string& key) const {
  const json* value = find(object, key);
  if (value == nullptr) (*this / key).fail("missing required field");
  return *value;
}

void JsonField::only(const json& object, std::initializer_list<const char*> known) const {
  for (const auto& [key, member] : object.items()) {
    bool found = false;
    for (const char* name : known) found = found || key == name;
    if (!found) (*this / key).fail("unknown member");
  }
}

}  // namespace oscilab::daq

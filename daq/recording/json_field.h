#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

namespace oscilab::daq {

/// A JSON value as it appears in a message: its JSON text, shortened to 60 characters so that a
/// huge value cannot flood the message ("a number out of range" for one beyond a double).
std::string json_excerpt(const nlohmann::json& value);

/// Where a value sits in a JSON document: the file and the path inside it, and typed reads of the
/// value there. Each read that finds the wrong kind or range of value throws one InputError
/// naming the file, the path and the value, the form every InputError takes:
///   run1.json: channels[1].scale: expected a number, got "abc"
/// A document without a file of its own (an object inside another) gives an empty file name,
/// and then the message starts with the path: "live.rig.f0_n: expected a number, got "9"".
///
/// Readers are const and keep nothing: a JsonField is a cheap value, made per member as a parser
/// descends (`field / "channels"`, `field[1]`).
class JsonField {
 public:
  explicit JsonField(std::string file, std::string path = "")
      : file_(std::move(file)), path_(std::move(path)) {}

  /// The member `key` of this value's object: "a.b" / "c" is "a.b.c".
  JsonField operator/(const std::string& key) const;
  /// The element `index` of this value's array: "a" [1] is "a[1]".
  JsonField operator[](std::size_t index) const;
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  /// "FILE: PATH" (without the parts that are empty), for messages made elsewhere.
  std::string where() const;

  /// Throws InputError "FILE: PATH: problem" (without the parts that are empty).
  [[noreturn]] void fail(const std::string& problem) const;

  const nlohmann::json& object(const nlohmann::json& value) const;
  const nlohmann::json& array(const nlohmann::json& value) const;
  std::string string(const nlohmann::json& value) const;
  bool boolean(const nlohmann::json& value) const;
  /// Any number (a JSON number beyond a double's range reads as ±infinity).
  double number(const nlohmann::json& value) const;
  double finite_number(const nlohmann::json& value) const;
  /// A finite number > 0.
  double positive_number(const nlohmann::json& value) const;
  /// A JSON integer ≥ min.
  long integer(const nlohmann::json& value, long min) const;
  /// A JSON integer from 0 to max (≤ INT_MAX).
  int whole_number(const nlohmann::json& value, std::int64_t max) const;

  /// The member `key` of the object `object` (this value), or null when it has none.
  static const nlohmann::json* find(const nlohmann::json& object, const std::string& key);
  /// The member `key` of the object `object` (this value); fails at this / key when missing.
  const nlohmann::json& require(const nlohmann::json& object, const std::string& key) const;
  /// Fails at this / key for the first member of `object` (this value) not in `known`.
  void only(const nlohmann::json& object, std::initializer_list<const char*> known) const;

 private:
  std::string file_;
  std::string path_;
};

}  // namespace oscilab::daq

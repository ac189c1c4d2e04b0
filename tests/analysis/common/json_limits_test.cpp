#include "analysis/common/json_limits.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "analysis/model/model_json.h"
#include "tests/input_error_of.h"

namespace oscilab {
namespace {

std::string nested_arrays(std::size_t depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

TEST(JsonLimits, AcceptsNestingUpToTheLimitAndRefusesOneLevelMore) {
  EXPECT_EQ(json_limit_violation(nested_arrays(kMaxJsonDepth)), "");
  EXPECT_EQ(json_limit_violation("{\"a\": " + nested_arrays(kMaxJsonDepth - 1) + "}"), "");
  EXPECT_EQ(json_limit_violation(nested_arrays(kMaxJsonDepth + 1)),
            "JSON nested deeper than 64 levels (at byte 64)");
  // Siblings do not add up: depth is nesting, not the count of brackets.
  std::string siblings = "[";
  for (int i = 0; i < 1000; ++i) siblings += "[],";
  siblings += "[]]";
  EXPECT_EQ(json_limit_violation(siblings), "");
}

TEST(JsonLimits, BracketsInsideStringsDoNotCount) {
  // A string full of brackets and an escaped quote: one level of nesting.
  const std::string text = "{\"notes\": \"\\\"" + std::string(1000, '[') + "\\\\\"}";
  EXPECT_EQ(json_limit_violation(text), "");
  EXPECT_EQ(parse_json_within_limits(text, "x.json")["notes"].get<std::string>().size(), 1002u);
}

TEST(JsonLimits, RefusesTextOverTheSizeLimit) {
  EXPECT_EQ(json_limit_violation("[1, 2, 3]", kMaxJsonDepth, 8),
            "9 bytes of JSON exceed the limit of 8");
}

TEST(JsonLimits, ADepthBombIsOneInputErrorNamingWhereNotAStackOverflow) {
  const std::string bomb = "{\"junk\": " + nested_arrays(100000) + "}";
  EXPECT_EQ(testing::input_error_of([&] { parse_json_within_limits(bomb, "run1.json"); }),
            "run1.json: JSON nested deeper than 64 levels (at byte 72)");
  const std::string message =
      testing::input_error_of([&] { parse_json_within_limits("{\"a\": 1", "run1.json"); });
  EXPECT_EQ(message.rfind("run1.json: malformed JSON: ", 0), 0u) << message;
}

TEST(JsonLimits, LoadModelRefusesADepthBombNamingTheFile) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "oscilab_json_limits_model.json").string();
  {
    std::ofstream out(path);
    out << "{\"mass_kg\": 0.26, \"terms\": [], \"junk\": " << nested_arrays(100000) << "}";
  }
  EXPECT_EQ(testing::input_error_of([&] { analysis::load_model(path); }),
            path + ": JSON nested deeper than 64 levels (at byte 102)");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace oscilab

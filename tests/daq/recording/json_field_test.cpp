#include "daq/recording/json_field.h"

#include <limits>

#include <gtest/gtest.h>

#include "tests/input_error_of.h"

namespace oscilab::daq {
namespace {

using nlohmann::json;
using oscilab::testing::input_error_of;

TEST(JsonField, ThrowsInputErrorNamingTheFileTheFieldPathAndTheBadValue) {
  const JsonField root("session.json");
  EXPECT_EQ(input_error_of([&] { (root / "plots" / "z_range").number(json("abc")); }),
            "session.json: plots.z_range: expected a number, got \"abc\"");
  EXPECT_EQ(input_error_of([&] { ((root / "channels")[1] / "unit").string(json(3)); }),
            "session.json: channels[1].unit: expected a string, got 3");
  EXPECT_EQ(input_error_of([&] { root.object(json::array()); }),
            "session.json: expected an object, got []");
}

TEST(JsonField, AnObjectWithoutAFileOfItsOwnIsNamedByItsPath) {
  const JsonField live("", "live");
  EXPECT_EQ(input_error_of([&] { (live / "jack" / "server").string(json(3)); }),
            "live.jack.server: expected a string, got 3");
  EXPECT_EQ((live / "rig").where(), "live.rig");
  EXPECT_EQ((JsonField("run1.json") / "rate").where(), "run1.json: rate");
}

TEST(JsonField, ShortensAHugeValueAndNamesANumberOutOfRange) {
  const std::string message =
      input_error_of([] { JsonField("a.json", "x").number(json(std::string(500, 'z'))); });
  EXPECT_LT(message.size(), 120u) << message;
  EXPECT_NE(message.find("..."), std::string::npos) << message;
  EXPECT_EQ(json_excerpt(json(std::numeric_limits<double>::infinity())), "a number out of range");
  EXPECT_EQ(input_error_of([] {
              JsonField("a.json", "x").finite_number(json(std::numeric_limits<double>::infinity()));
            }),
            "a.json: x: expected a finite number, got a number out of range");
}

TEST(JsonField, ReadsEachKindAndRefusesTheWrongRange) {
  const JsonField f("a.json", "f");
  EXPECT_EQ(f.number(json(2.5)), 2.5);
  EXPECT_EQ(f.positive_number(json(3)), 3.0);
  EXPECT_TRUE(f.boolean(json(true)));
  EXPECT_EQ(f.integer(json(4), 1), 4);
  EXPECT_EQ(f.whole_number(json(7), 10), 7);
  EXPECT_EQ(input_error_of([&] { f.positive_number(json(0)); }),
            "a.json: f: expected a positive number, got 0");
  EXPECT_EQ(input_error_of([&] { f.boolean(json("yes")); }),
            "a.json: f: expected true or false, got \"yes\"");
  EXPECT_EQ(input_error_of([&] { f.integer(json(2.5), 0); }),
            "a.json: f: expected an integer, got 2.5");
  EXPECT_EQ(input_error_of([&] { f.integer(json(0), 1); }),
            "a.json: f: expected an integer \u2265 1, got 0");
  EXPECT_EQ(input_error_of([&] { f.whole_number(json(-1), 10); }),
            "a.json: f: expected a whole number from 0 to 10, got -1");
  EXPECT_EQ(input_error_of([&] { f.array(json(1)); }), "a.json: f: expected an array, got 1");
}

TEST(JsonField, NamesAMissingOrUnknownMember) {
  const JsonField f("a.json", "channel");
  const json object = {{"name", "y"}, {"colour", "red"}};
  EXPECT_EQ(f.require(object, "name"), "y");
  EXPECT_EQ(JsonField::find(object, "unit"), nullptr);
  EXPECT_EQ(input_error_of([&] { f.require(object, "unit"); }),
            "a.json: channel.unit: missing required field");
  EXPECT_EQ(input_error_of([&] {
              f.only(object, {"name", "unit"});
            }),
            "a.json: channel.colour: unknown member");
}

}  // namespace
}  // namespace oscilab::daq

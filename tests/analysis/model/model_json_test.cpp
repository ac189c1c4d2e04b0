#include "analysis/model/model_json.h"

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/reference_models.h"

namespace oscilab::analysis {
namespace {

using nlohmann::json;

TEST(ModelJson, RoundTripKeepsEveryTermAndValue) {
  const Model model = paper_model();
  const Model back = model_from_json(json::parse(model.to_json().dump()), "m.json");
  EXPECT_EQ(back.to_json(), model.to_json());
  for (double z : {-0.03, 0.0, 0.025}) {
    for (double v : {-0.1, 0.0, 0.02}) {
      EXPECT_EQ(back.restoring_force(z, v, nullptr), model.restoring_force(z, v, nullptr));
    }
  }
}

std::string error_of(const json& object) {
  try {
    model_from_json(object, "m.json");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(ModelJson, ErrorsNameTheFieldAndValue) {
  json model = paper_model().to_json();
  model["terms"][1]["type"] = "magic-friction";
  EXPECT_EQ(error_of(model), "m.json: terms[1].type: unknown term type \"magic-friction\"");

  model = paper_model().to_json();
  model["terms"][2]["c_ns_m"] = "two";
  EXPECT_EQ(error_of(model), "m.json: terms[2].c_ns_m: expected a number, got \"two\"");

  model = paper_model().to_json();
  model["terms"][1]["ks"] = 0.5;
  EXPECT_NE(error_of(model).find("m.json: terms[1]: position-dependent-friction: ks"),
            std::string::npos);

  model = paper_model().to_json();
  model.erase("mass_kg");
  EXPECT_EQ(error_of(model), "m.json: missing field \"mass_kg\"");
}

}  // namespace
}  // namespace oscilab::analysis

#include "daq/recording/formats/tdms_scales.h"

#include <cmath>

#include "analysis/common/input_error.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq::tdms {
namespace {

// The input source of a scale that reads the stored (raw) values.
constexpr std::uint32_t kScaleInputRaw = 0xFFFFFFFF;

}  // namespace

std::optional<double> number_property(const nlohmann::json& properties, const std::string& name) {
  const auto found = properties.find(name);
  if (found == properties.end() || !found->is_number()) return std::nullopt;
  return found->get<double>();
}

ScalePlan scale_plan(const TdmsObject& object, const std::string& path) {
  const nlohmann::json& properties = object.properties;
  const std::string where = path + ": " + in_quotes(signal_name(object)) + ": ";
  ScalePlan plan;
  const auto status = properties.find("NI_Scaling_Status");
  if (status != properties.end() && status->is_string() && *status == "scaled") return plan;
  const std::optional<double> count = number_property(properties, "NI_Number_Of_Scales");
  if (!count || *count == 0) return plan;
  if (!(*count >= 1 && *count <= 4294967295.0) || *count != std::floor(*count)) {
    throw InputError(where + "NI_Number_Of_Scales is " + number_text(*count));
  }
  auto scale = static_cast<std::uint32_t>(*count - 1);
  std::vector<std::pair<double, double>> from_last;
  for (;;) {
    const std::string prefix = "NI_Scale[" + std::to_string(scale) + "]_";
    const auto type = properties.find(prefix + "Scale_Type");
    if (type == properties.end()) {
      // A scale the properties do not describe: the values of the DAQmx scaler of that ID.
      if (object.first_index && object.first_index->daqmx) plan.scale_id = scale;
      break;
    }
    if (!type->is_string() || *type != "Linear") {
      throw InputError(where + prefix + "Scale_Type is " + type->dump().substr(0, 60) +
                       ": only Linear scales are read");
    }
    const std::optional<double> slope = number_property(properties, prefix + "Linear_Slope");
    const std::optional<double> intercept =
        number_property(properties, prefix + "Linear_Y_Intercept");
    if (!slope || !intercept) {
      throw InputError(where + prefix + "Scale_Type is \"Linear\", but " + prefix +
                       "Linear_Slope or " + prefix + "Linear_Y_Intercept is missing");
    }
    from_last.emplace_back(*slope, *intercept);
    const std::optional<double> source =
        number_property(properties, prefix + "Linear_Input_Source");
    if (!source || *source == kScaleInputRaw) break;
    if (!(*source >= 0 && *source < scale) || *source != std::floor(*source)) {
      throw InputError(where + prefix + "Linear_Input_Source " + number_text(*source) +
                       " is not an earlier scale");
    }
    scale = static_cast<std::uint32_t>(*source);
  }
  plan.steps.assign(from_last.rbegin(), from_last.rend());
  return plan;
}

}  // namespace oscilab::daq::tdms

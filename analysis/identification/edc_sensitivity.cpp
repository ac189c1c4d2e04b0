#include "analysis/identification/edc_sensitivity.h"

#include <algorithm>

#include "analysis/common/input_error.h"
#include "analysis/common/parallel_for.h"

namespace oscilab::analysis {

std::vector<SensitivityCurve> edc_sensitivity(const EdcObjective& objective,
                                              const Eigen::VectorXd& theta,
                                              const std::vector<double>& factors, int threads) {
  const ModelForm& form = objective.form();
  // Parameter groups: the f_d values of eq. (9) move together (k_d), the others alone.
  struct Group {
    std::string name;
    std::vector<int> indices;
  };
  std::vector<Group> groups;
  Group kd{"kd", {}};
  for (int i = 0; i < form.size(); ++i) {
    const std::string& name = form.parameters()[i].name;
    if (name.rfind("fd_", 0) == 0) {
      kd.indices.push_back(i);
    } else {
      groups.push_back({name, {i}});
    }
  }
  if (!kd.indices.empty()) groups.insert(groups.begin(), kd);

  std::vector<SensitivityCurve> curves;
  for (const Group& g : groups) {
    for (double factor : factors) {
      if (!(factor > 0.0)) throw InputError("sensitivity: factors must be positive");
      for (const EdcGroup& data : objective.data().groups) {
        SensitivityCurve curve;
        curve.parameter = g.name;
        curve.factor = factor;
        curve.positive_well = data.positive_well;
        curve.freq_hz = data.freq_hz;
        for (const MeasuredLevel& level : data.levels) curve.f0_n.push_back(level.f0_n);
        curves.push_back(std::move(curve));
      }
    }
  }
  parallel_for(curves.size(), threads, [&](std::size_t c) {
    SensitivityCurve& curve = curves[c];
    Eigen::VectorXd scaled = theta;
    const Group& g = *std::find_if(groups.begin(), groups.end(),
                                   [&](const Group& x) { return x.name == curve.parameter; });
    for (int i : g.indices) {
      scaled(i) = form.parameters()[i].name == "ks" ? 1.0 + curve.factor * (theta(i) - 1.0)
                                                    : curve.factor * theta(i);
    }
    try {
      curve.edc_j =
          objective.edc_at(form.build(scaled), curve.positive_well, curve.freq_hz, curve.f0_n);
    } catch (const InputError&) {
      curve.ok = false;
      curve.edc_j.assign(curve.f0_n.size(), 0.0);
    }
    for (double s : curve.edc_j) curve.ok = curve.ok && s != 0.0;
  });
  return curves;
}

}  // namespace oscilab::analysis

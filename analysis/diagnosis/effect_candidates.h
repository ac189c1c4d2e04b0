#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/model_form.h"

namespace oscilab::analysis {

/// A physical effect a diagnosis may add (docs/contracts.md §4 names): the term, its free
/// parameters with bounds scaled to the data, starting points to scan, and what its fingerprint
/// looks like.
struct EffectCandidate {
  std::string effect;  // e.g. "quadratic-damping"
  /// The term added; nullptr for an effect that enters as a change of a law the model holds
  /// (`changes_type`), e.g. presliding as the friction's own regime.
  std::unique_ptr<ModelTerm> term;
  std::vector<FreeParameter> free;
  std::vector<Eigen::VectorXd> scan;  // starting values of the free parameters, tried in turn
  /// Expected log–log slope of the energy it adds against the response amplitude (Coulomb 1,
  /// quadratic damping 3, cubic 4, presliding hysteresis 3 for small loops, Stribeck excess ≤ 1:
  /// it fades as the velocity grows); NaN for stiffness effects.
  double expected_slope = 0.0;
  bool stiffness = false;
  int stiffness_power = 0;
  /// How the effect enters: "added-term", or "friction-regime" (a change of the friction law
  /// the model holds). One effect may come in several embodiments, tried side by side.
  std::string embodiment = "added-term";
  std::string changes_type = "";  // the changed term's type when term is nullptr
  /// Whether the effect vanishes inside its bounds (its strength at 0, or at a log-scale lower
  /// bound): a later refit may then withdraw it.
  bool can_vanish = true;

  /// The form extended by this candidate (the term added, or the law changed), its new free
  /// parameters starting at `start` (their count).
  ModelForm extend(const ModelForm& form, const Eigen::VectorXd& start) const;
};

/// Every effect of the vocabulary that the form does not already hold, with bounds from the
/// data's scales: the largest EDC S_max, response amplitude Z_max and forcing f0_max, and the
/// forcing frequency ω. Effects the form holds (the paper's form has viscous damping and the
/// position-dependent friction) are not offered again.
std::vector<EffectCandidate> effect_candidates(const ModelForm& form, const EdcDataset& data);

/// The vocabulary of docs/contracts.md §4, `none` last.
const std::vector<std::string>& effect_vocabulary();

}  // namespace oscilab::analysis

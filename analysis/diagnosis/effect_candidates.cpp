#include "analysis/diagnosis/effect_candidates.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "analysis/model/coulomb_friction.h"
#include "analysis/model/dahl_friction.h"
#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/position_dependent_friction.h"
#include "analysis/model/velocity_power_damping.h"
#include "analysis/model/viscous_damping.h"

namespace oscilab::analysis {
namespace {

// Starting values: a fraction of the bound, log-spaced from 1e-3 to 0.3 of it.
std::vector<Eigen::VectorXd> log_scan(double upper, int count) {
  std::vector<Eigen::VectorXd> out;
  for (int i = 0; i < count; ++i) {
    const double fraction = 1e-3 * std::pow(300.0, static_cast<double>(i) / (count - 1));
    out.push_back(Eigen::VectorXd::Constant(1, fraction * upper));
  }
  return out;
}

bool form_has(const ModelForm& form, const std::string& type) {
  for (const auto& term : form.base().terms()) {
    if (term->type() == type) return true;
  }
  return false;
}

// The form's position-dependent friction when it still slides (no presliding regime yet).
bool form_has_sliding_friction(const ModelForm& form) {
  for (const auto& term : form.base().terms()) {
    const auto* friction = dynamic_cast<const PositionDependentFriction*>(term.get());
    if (friction && !friction->presliding()) return true;
  }
  return false;
}

}  // namespace

ModelForm EffectCandidate::extend(const ModelForm& form, const Eigen::VectorXd& start) const {
  ModelForm extended = form;
  if (term) {
    extended.add_term(term->clone(), free);
  } else {
    extended.change_term(changes_type, free,
                         std::vector<double>(start.data(), start.data() + start.size()));
  }
  return extended;
}

const std::vector<std::string>& effect_vocabulary() {
  static const std::vector<std::string> names = {"viscous-damping",
                                                 "coulomb-friction",
                                                 "position-dependent-friction",
                                                 "stribeck-friction",
                                                 "quadratic-damping",
                                                 "cubic-damping",
                                                 "presliding-hysteresis",
                                                 "quadratic-stiffness",
                                                 "cubic-stiffness",
                                                 "quintic-stiffness",
                                                 "none"};
  return names;
}

namespace {

// The data's scales the candidates' bounds come from: the largest EDC, amplitude and forcing, and
// the forcing's angular frequency.
struct DataScales {
  double s_max = 0.0, z_max = 0.0, f0_max = 0.0, omega = 0.0;
};

DataScales data_scales(const EdcDataset& data) {
  DataScales d;
  double freq_hz = 0.0;
  for (const EdcGroup& g : data.groups) {
    freq_hz = std::max(freq_hz, g.freq_hz);
    for (const MeasuredLevel& m : g.levels) {
      d.s_max = std::max(d.s_max, m.edc_j);
      d.z_max = std::max(d.z_max, m.amplitude_m);
      d.f0_max = std::max(d.f0_max, m.f0_n);
    }
  }
  d.omega = 2.0 * std::numbers::pi * freq_hz;
  if (!(d.z_max > 0.0)) d.z_max = 1e-3;
  if (!(d.s_max > 0.0)) d.s_max = 1e-3;
  if (!(d.f0_max > 0.0)) d.f0_max = 1.0;
  return d;
}

// Added dissipation: Coulomb friction and viscous, quadratic and cubic damping, each bounded by
// what would dissipate twice the largest EDC at the largest amplitude.
void add_dissipation_candidates(const ModelForm& form, const DataScales& d,
                                const std::function<void(EffectCandidate)>& add) {
  const double s_max = d.s_max, z_max = d.z_max, f0_max = d.f0_max, omega = d.omega;
  {
    // Coulomb dissipates 4 F_c Z: F_c up to twice the largest EDC over 4 Z_max. On top of the
    // paper's f_d(z) it is a position-independent part (γ of eq. (6) absorbs much of it).
    const double fc_max = std::min(f0_max, 2.0 * s_max / (4.0 * z_max));
    add({"coulomb-friction",
         std::make_unique<CoulombFriction>(0.0, 1e-3),
         {{"fc_n", 0.0, fc_max, false}},
         log_scan(fc_max, 6),
         1.0});
  }
  if (!form_has(form, "viscous-damping")) {
    const double c_max = 2.0 * s_max / (std::numbers::pi * omega * z_max * z_max);
    add({"viscous-damping",
         std::make_unique<ViscousDamping>(0.0),
         {{"c_ns_m", 0.0, c_max, false}},
         log_scan(c_max, 6),
         2.0});
  }
  {
    // 8/3 c2 ω² Z³ and 3π/4 c3 ω³ Z⁴ up to twice the largest EDC.
    const double c2_max = 2.0 * s_max / (8.0 / 3.0 * omega * omega * std::pow(z_max, 3));
    add({"quadratic-damping",
         std::make_unique<VelocityPowerDamping>(2, 0.0),
         {{"c2_ns2_m2", 0.0, c2_max, false}},
         log_scan(c2_max, 6),
         3.0});
    const double c3_max =
        2.0 * s_max / (0.75 * std::numbers::pi * std::pow(omega, 3) * std::pow(z_max, 4));
    add({"cubic-damping",
         std::make_unique<VelocityPowerDamping>(3, 0.0),
         {{"c3_ns3_m3", 0.0, c3_max, false}},
         log_scan(c3_max, 6),
         4.0});
  }
}

// Friction laws on top of the form's: a Stribeck excess and a Dahl presliding element.
void add_friction_law_candidates(const DataScales& d,
                                 const std::function<void(EffectCandidate)>& add) {
  const double s_max = d.s_max, z_max = d.z_max, f0_max = d.f0_max;
  {
    // Stribeck excess: force up to the largest forcing, velocity scale over two decades.
    EffectCandidate c{"stribeck-friction",
                      std::make_unique<StribeckFriction>(0.0, 1e-2),
                      {{"fs_n", 0.0, f0_max, false}, {"vs_m_s", 1e-3, 0.1, true}},
                      {},
                      0.5};
    for (double fs : {0.02, 0.1, 0.3}) {
      for (double vs : {2e-3, 1e-2, 4e-2}) {
        Eigen::VectorXd v(2);
        v << fs * f0_max, vs;
        c.scan.push_back(v);
      }
    }
    add(std::move(c));
  }
  {
    // Dahl: F_c up to the largest forcing, presliding stiffness σ0 up to 1e4 F_c,max/Z_max (the
    // presliding length F_c/σ0 down to 1e-4 of the largest amplitude) and at most F_c,max / 1 µm:
    // a stiffer contact rings beyond what harmonic balance resolves (as for the friction regime
    // below, contact_resolving_harmonics).
    const double fc_max = std::min(f0_max, 2.0 * s_max / (4.0 * z_max));
    const double sigma_lo = fc_max / z_max,
                 sigma_hi = std::max(2.0 * sigma_lo, std::min(1e4 * fc_max / z_max, fc_max / 1e-6));
    EffectCandidate c{
        "presliding-hysteresis",
        std::make_unique<DahlFriction>(0.1 * fc_max, std::sqrt(sigma_lo * sigma_hi)),
        {{"fc_n", 1e-4 * fc_max, fc_max, true}, {"sigma0_n_m", sigma_lo, sigma_hi, true}},
        {},
        3.0};
    for (double f : {0.01, 0.05, 0.2}) {
      for (double length : {0.003, 0.03, 0.3}) {  // F_c/σ0 as a fraction of Z_max
        Eigen::VectorXd v(2);
        v << f * fc_max, std::clamp(f * fc_max / (length * z_max), sigma_lo, sigma_hi);
        c.scan.push_back(v);
      }
    }
    add(std::move(c));
  }
}

// Presliding as the friction's own regime, when the form has a sliding friction.
void add_friction_regime_candidate(const ModelForm& form, const DataScales& d,
                                   std::vector<EffectCandidate>& out) {
  const double z_max = d.z_max;
  if (form_has_sliding_friction(form)) {
    // Presliding as the friction's own regime (eqs. (5)–(6) with a presliding length δ): the
    // contact's Coulomb part turns into a Dahl state of the same magnitude f_d(z). δ from 1 µm
    // (below it harmonic balance does not reliably pass the stick–slip transition, see
    // contact_resolving_harmonics; and tanh(4ż/v_t) already spreads the reversal over about a
    // micrometre at these amplitudes) to the largest amplitude. The sliding law is not inside
    // these bounds, so the effect never vanishes in a refit (can_vanish).
    const double length_lo = 1e-6, length_hi = std::max(1e-3, z_max);
    EffectCandidate c{"presliding-hysteresis",
                      nullptr,
                      {{"presliding_length_m", length_lo, length_hi, true}},
                      {},
                      3.0};
    c.can_vanish = false;
    c.embodiment = "friction-regime";
    c.changes_type = "position-dependent-friction";
    for (double length : {1e-6, 3e-6, 1e-5, 3e-5, 1e-4, 3e-4}) {
      if (length < length_hi) c.scan.push_back(Eigen::VectorXd::Constant(1, length));
    }
    out.push_back(std::move(c));
  }
}

// Stiffness powers the form does not identify already.
void add_stiffness_candidates(const ModelForm& form, const DataScales& d,
                              std::vector<EffectCandidate>& out) {
  const double z_max = d.z_max, f0_max = d.f0_max;
  // Stiffness powers c z^p: bounded so that c Z_ref^p stays within ten times the largest forcing,
  // with Z_ref the largest |z| the wells reach (the wells' positions plus the largest amplitude):
  // a stiffness power far stronger than the forcing would have moved the wells out of the test.
  double z_ref = z_max;
  for (const auto& well : form.base().equilibria())
    z_ref = std::max(z_ref, std::abs(well.z_m) + z_max);
  const struct {
    const char* name;
    int power;
  } powers[] = {{"quadratic-stiffness", 2}, {"cubic-stiffness", 3}, {"quintic-stiffness", 5}};
  for (const auto& p : powers) {
    // A power the form's identified stiffness already holds is no missing effect.
    if (form.frees_stiffness_power(p.power)) continue;
    const double bound = 10.0 * f0_max / std::pow(z_ref, p.power);
    std::vector<double> coefficients(static_cast<std::size_t>(p.power) + 1, 0.0);
    EffectCandidate c{p.name,
                      std::make_unique<PolynomialStiffness>(coefficients),
                      {{"c" + std::to_string(p.power), -bound, bound, false}},
                      {},
                      std::numeric_limits<double>::quiet_NaN(),
                      true,
                      p.power};
    for (double f : {-0.1, -0.01, -0.001, 0.001, 0.01, 0.1})
      c.scan.push_back(Eigen::VectorXd::Constant(1, f * bound));
    out.push_back(std::move(c));
  }
}

}  // namespace

std::vector<EffectCandidate> effect_candidates(const ModelForm& form, const EdcDataset& data) {
  const DataScales scales = data_scales(data);
  std::vector<EffectCandidate> out;
  const std::function<void(EffectCandidate)> add = [&](EffectCandidate c) {
    if (!form_has(form, c.term->type())) out.push_back(std::move(c));
  };
  add_dissipation_candidates(form, scales, add);
  add_friction_law_candidates(scales, add);
  add_friction_regime_candidate(form, scales, out);
  add_stiffness_candidates(form, scales, out);
  return out;
}

}  // namespace oscilab::analysis

#pragma once

#include "analysis/diagnosis/diagnosis.h"
#include "analysis/figures/figure.h"

namespace oscilab::figures {

/// The EDC residual per level in units of its σ, (S_mes − S_mod)/σ against f0, for the baseline
/// and the final model of a diagnosis, one panel per well, with the ±3σ band: where the
/// baseline misses and whether the named effect closed the gap.
Figure residual_figure(const analysis::DiagnosisResult& result);

/// The energy the baseline misses, log10 |S_mes − S_mod| against log10 |Z1|: its slope names the
/// missing dissipation law (1 Coulomb, 2 viscous, 3 quadratic damping or presliding, 4 cubic).
Figure missing_energy_figure(const analysis::DiagnosisResult& result);

}  // namespace oscilab::figures

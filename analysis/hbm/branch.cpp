#include "analysis/hbm/branch.h"

#include <complex>
#include <fstream>
#include <ostream>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

const char* marker_name(PointMarker marker) {
  switch (marker) {
    case PointMarker::None:
      return "";
    case PointMarker::Start:
      return "start";
    case PointMarker::End:
      return "end";
    case PointMarker::Landing:
      return "landing";
    case PointMarker::Fold:
      return "fold";
    case PointMarker::PeriodDoubling:
      return "period-doubling";
    case PointMarker::BranchPoint:
      return "branch-point";
  }
  return "";
}

std::vector<BranchEvent> Branch::events_of(PointMarker kind) const {
  std::vector<BranchEvent> out;
  for (const BranchEvent& e : events) {
    if (e.kind == kind) out.push_back(e);
  }
  return out;
}

void write_branch_csv(const Branch& branch, std::ostream& out) {
  out << "f0_n,amp_m,z1_abs_m,phase_rad,edc_j,stable,freq_hz,edc_dissipation_j,mu1_abs,mu2_abs,"
         "mu1_re,mu1_im,mu2_re,mu2_im,marker,newton_iterations\n";
  out.precision(10);
  for (const BranchPoint& p : branch.points) {
    const HbmMeasures& m = p.measures;
    out << p.f0_n << ',' << m.amp_m << ',' << std::abs(m.z1_m) << ',' << std::arg(m.z1_m) + 0.0
        << ',' << m.edc_j + 0.0 << ',' << (p.stability_known && p.floquet.stable ? 1 : 0) << ','
        << p.freq_hz << ',' << m.edc_dissipation_j << ',';
    if (p.stability_known) {
      const auto& mu = p.floquet.multipliers;
      out << std::abs(mu[0]) << ',' << std::abs(mu[1]) << ',' << mu[0].real() << ',' << mu[0].imag()
          << ',' << mu[1].real() << ',' << mu[1].imag() << ',';
    } else {
      out << ",,,,,,";
    }
    out << marker_name(p.marker) << ',' << p.newton_iterations << '\n';
  }
}

void write_branch_csv(const Branch& branch, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw InputError(path + ": cannot write");
  write_branch_csv(branch, file);
  if (!file) throw InputError(path + ": write failed");
}

}  // namespace oscilab::analysis

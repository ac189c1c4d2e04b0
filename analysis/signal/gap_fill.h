#pragma once

#include <Eigen/Core>

namespace oscilab::analysis {

/// Replaces every run of non-finite samples by the straight line between the finite samples on
/// either side (the nearest finite sample at an end), so that whole-record spectral processing
/// stays finite. The filled samples carry no information: callers exclude them from results
/// (MeasurementChannels::excluded). Returns the number of samples replaced; an all-non-finite
/// signal becomes zeros.
long fill_non_finite(Eigen::VectorXd& x);

}  // namespace oscilab::analysis

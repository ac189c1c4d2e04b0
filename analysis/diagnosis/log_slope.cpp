#include "analysis/diagnosis/log_slope.h"

#include <cmath>
#include <limits>

#include <boost/math/distributions/students_t.hpp>

namespace oscilab::analysis {

LogSlope log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  LogSlope out;
  std::vector<double> lx, ly;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (x[i] > 0.0 && y[i] > 0.0 && std::isfinite(x[i]) && std::isfinite(y[i])) {
      lx.push_back(std::log(x[i]));
      ly.push_back(std::log(y[i]));
    }
  }
  out.points = static_cast<int>(lx.size());
  if (out.points < 2) return out;
  const double n = out.points;
  double mx = 0.0, my = 0.0;
  for (int i = 0; i < out.points; ++i) {
    mx += lx[i] / n;
    my += ly[i] / n;
  }
  double sxx = 0.0, sxy = 0.0;
  for (int i = 0; i < out.points; ++i) {
    sxx += (lx[i] - mx) * (lx[i] - mx);
    sxy += (lx[i] - mx) * (ly[i] - my);
  }
  const double inf = std::numeric_limits<double>::infinity();
  if (!(sxx > 0.0)) {
    out.points = 1;  // all x equal: no slope
    return out;
  }
  out.slope = sxy / sxx;
  if (out.points > 2) {
    double sse = 0.0;
    for (int i = 0; i < out.points; ++i) {
      const double e = ly[i] - my - out.slope * (lx[i] - mx);
      sse += e * e;
    }
    out.standard_error = std::sqrt(sse / (n - 2.0) / sxx);
    const double t = boost::math::quantile(boost::math::students_t(n - 2.0), 0.975);
    out.lower_95 = out.slope - t * out.standard_error;
    out.upper_95 = out.slope + t * out.standard_error;
  } else {
    out.standard_error = inf;
    out.lower_95 = -inf;
    out.upper_95 = inf;
  }
  return out;
}

}  // namespace oscilab::analysis

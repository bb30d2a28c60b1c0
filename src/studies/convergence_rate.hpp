#pragma once
// The observed order of convergence of a study's error series.
#include <cmath>
#include <vector>

namespace periadapt {

// Least-squares slope of log(err) against log(nodes), negated: the rate at which the error falls
// with the node count.
inline double fitted_rate(const std::vector<double>& nodes, const std::vector<double>& err) {
  const double n = static_cast<double>(nodes.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const double x = std::log(nodes[k]), y = std::log(err[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace periadapt

#include "analysis/rayleigh_speed.hpp"

#include <cmath>

namespace periadapt {

double rayleigh_speed(int dim, PlaneCondition plane, double E, double nu, double rho) {
  if (dim < 2 || !(E > 0) || !(rho > 0)) return 0.0;
  const double mu = E / (2.0 * (1.0 + nu));
  const double cs = std::sqrt(mu / rho);
  const double k2 = mu / p_wave_modulus(dim, plane, E, nu);  // (c_s / c_p)^2
  // R(x) = (2 - x^2)^2 - 4 sqrt(1 - k2 x^2) sqrt(1 - x^2) is negative at small x
  // (R ~ -2 (1 - k2) x^2) and 1 at x = 1: bisection on (0, 1) finds its one root there.
  auto R = [&](double x) {
    const double x2 = x * x;
    return (2.0 - x2) * (2.0 - x2) - 4.0 * std::sqrt(1.0 - k2 * x2) * std::sqrt(1.0 - x2);
  };
  double lo = 1e-3, hi = 1.0 - 1e-15;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (R(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) * cs;
}

}  // namespace periadapt

#include "discretize/partial_volume.hpp"

#include <algorithm>
#include <cmath>

namespace periadapt {

double quadrature_search_radius(Quadrature q, int dim, double delta, double dx) {
  if (q != Quadrature::Subcell) return delta;
  return delta + 0.5 * std::sqrt(static_cast<double>(dim)) * dx;
}

double subcell_fraction(int dim, const std::array<double, 3>& xi, double delta, double dx,
                        double rotation) {
  std::array<double, 3> p = xi;
  if (dim == 2 && rotation != 0.0) {  // into the lattice frame, where cells are axis-aligned
    const double c = std::cos(rotation), s = std::sin(rotation);
    p = {c * xi[0] + s * xi[1], -s * xi[0] + c * xi[1], 0.0};
  }
  double r2 = 0;
  for (int d = 0; d < dim; ++d) r2 += p[d] * p[d];
  const double r = std::sqrt(r2);
  const double half_diag = 0.5 * std::sqrt(static_cast<double>(dim)) * dx;
  if (r + half_diag <= delta) return 1.0;
  if (r - half_diag >= delta) return 0.0;
  if (dim == 1) {  // exact
    const double lo = std::abs(p[0]) - 0.5 * dx;
    return std::clamp((delta - lo) / dx, 0.0, 1.0);
  }
  const int n = dim == 2 ? 32 : 12;
  const double h = dx / n, d2 = delta * delta;
  long inside = 0;
  for (int k = 0; k < (dim == 3 ? n : 1); ++k) {
    const double z = dim == 3 ? p[2] - 0.5 * dx + (k + 0.5) * h : 0.0;
    for (int j = 0; j < n; ++j) {
      const double y = p[1] - 0.5 * dx + (j + 0.5) * h;
      for (int i = 0; i < n; ++i) {
        const double x = p[0] - 0.5 * dx + (i + 0.5) * h;
        inside += (x * x + y * y + z * z <= d2);
      }
    }
  }
  return static_cast<double>(inside) / std::pow(static_cast<double>(n), dim);
}

}  // namespace periadapt

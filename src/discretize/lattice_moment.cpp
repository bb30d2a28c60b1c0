#include "discretize/lattice_moment.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace periadapt {

double lattice_bond_moment(Quadrature rule, int dim, InfluenceShape shape, double m) {
  const bool exact_area = rule == Quadrature::Subcell || rule == Quadrature::IpaHybrid;
  const double reach = quadrature_search_radius(rule, dim, m, 1.0) * (1 + 1e-12);
  const int n = static_cast<int>(std::ceil(reach));
  double sum = 0;
  const int ny = dim >= 2 ? n : 0, nz = dim >= 3 ? n : 0;
  for (int i = -n; i <= n; ++i)
    for (int j = -ny; j <= ny; ++j)
      for (int k = -nz; k <= nz; ++k) {
        const std::array<double, 3> xi{double(i), double(j), double(k)};
        const double r = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
        if (r == 0 || r > reach) continue;
        const double beta = exact_area ? subcell_fraction(dim, xi, m, 1.0, 0.0)
                                       : partial_volume_factor(rule, std::min(r, m), m, 1.0);
        sum += influence(shape, std::min(r / m, 1.0)) * r * beta;
      }
  const double pi = std::numbers::pi;
  const double continuum = dim == 1   ? 2 * m * m * shape_moment(shape, 1)
                           : dim == 2 ? 2 * pi * m * m * m * shape_moment(shape, 2)
                                      : 4 * pi * m * m * m * m * shape_moment(shape, 3);
  return sum / continuum;
}

}  // namespace periadapt

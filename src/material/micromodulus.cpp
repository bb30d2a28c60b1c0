#include "material/micromodulus.hpp"

#include <cmath>
#include <numbers>

namespace periadapt {

double shape_moment(InfluenceShape s, int k) {
  const double kk = static_cast<double>(k);
  switch (s) {
    case InfluenceShape::Constant: return 1.0 / (kk + 1.0);
    case InfluenceShape::Triangular: return 1.0 / (kk + 1.0) - 1.0 / (kk + 2.0);
    case InfluenceShape::InvertedTriangular: return 1.0 / (kk + 2.0);
  }
  return 0.0;
}

double bond_based_poisson(int dim, PlaneCondition plane) {
  return (dim == 2 && plane == PlaneCondition::Stress) ? 1.0 / 3.0 : 0.25;
}

double classical_isotropic_energy(int dim, PlaneCondition plane, double E, double eps) {
  const double nu = bond_based_poisson(dim, plane);
  switch (dim) {
    case 1: return 0.5 * E * eps * eps;
    case 2:
      if (plane == PlaneCondition::Stress) return E / (1.0 - nu) * eps * eps;
      return E / ((1.0 + nu) * (1.0 - 2.0 * nu)) * eps * eps;
    default: return 1.5 * E / (1.0 - 2.0 * nu) * eps * eps;  // (9/2) K eps^2
  }
}

// Measure of the unit sphere surface in each dimension: 1D counts both directions.
static double sphere_measure(int dim) {
  switch (dim) {
    case 1: return 2.0;
    case 2: return 2.0 * std::numbers::pi;
    default: return 4.0 * std::numbers::pi;
  }
}

double micromodulus_c0(int dim, PlaneCondition plane, InfluenceShape shape, double E, double delta,
                       double thickness) {
  // W_pd = 1/4 * c0 * eps^2 * S_d * t * delta^(d+1) * M_d   (t = thickness or area, 3D: 1)
  const double t = (dim == 3) ? 1.0 : thickness;
  const double Wunit = classical_isotropic_energy(dim, plane, E, 1.0);
  return 4.0 * Wunit / (sphere_measure(dim) * t * std::pow(delta, dim + 1) * shape_moment(shape, dim));
}

double critical_stretch_from_g0(int dim, InfluenceShape shape, double c0, double delta,
                                double thickness, double G0) {
  // Energy of all bonds crossing a unit area, each at micropotential c s0^2 xi / 2:
  //  1D: G0 = t s0^2 c0 delta^3 M_2 / 2
  //  2D: G0 = t s0^2 c0 delta^4 M_3
  //  3D: G0 = pi/2 s0^2 c0 delta^5 M_4
  double k;
  switch (dim) {
    case 1: k = 0.5 * thickness * c0 * std::pow(delta, 3) * shape_moment(shape, 2); break;
    case 2: k = thickness * c0 * std::pow(delta, 4) * shape_moment(shape, 3); break;
    default: k = 0.5 * std::numbers::pi * c0 * std::pow(delta, 5) * shape_moment(shape, 4); break;
  }
  return std::sqrt(G0 / k);
}

double p_wave_modulus(int dim, PlaneCondition plane, double E, double nu) {
  if (dim == 1) return E;
  if (dim == 2 && plane == PlaneCondition::Stress) return E / (1.0 - nu * nu);
  return E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

std::string to_string(InfluenceShape s) {
  switch (s) {
    case InfluenceShape::Constant: return "constant";
    case InfluenceShape::Triangular: return "triangular";
    case InfluenceShape::InvertedTriangular: return "inverted_triangular";
  }
  return "?";
}

}  // namespace periadapt

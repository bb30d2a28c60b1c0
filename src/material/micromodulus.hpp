#pragma once
// PMB micromodulus c(xi) = c0 * g(xi/delta) and critical stretch, calibrated per dimension and
// plane condition by matching the classical strain-energy density under isotropic expansion
// (thesis Eq. 2.13; Bobaru et al. 2009 Eqs. 11-21) and the fracture energy G0 (thesis Eq. 2.15).
#include <string>

namespace periadapt {

enum class InfluenceShape { Constant, Triangular, InvertedTriangular };
enum class PlaneCondition { None, Stress, Strain };

// g(t), t = xi/delta in [0, 1].
inline double influence(InfluenceShape s, double t) {
  switch (s) {
    case InfluenceShape::Constant: return 1.0;
    case InfluenceShape::Triangular: return 1.0 - t;
    case InfluenceShape::InvertedTriangular: return t;
  }
  return 1.0;
}

// g(t) for a shape known at compile time (hot kernels); t may exceed 1 for cells partly covered
// beyond the horizon, where the shape is held at its edge value.
template <InfluenceShape S>
inline double influence_at(double t) {
  t = t < 1.0 ? t : 1.0;
  if constexpr (S == InfluenceShape::Constant) return 1.0;
  else if constexpr (S == InfluenceShape::Triangular) return 1.0 - t;
  else return t;
}

// Moment M_k = int_0^1 g(t) t^k dt.
double shape_moment(InfluenceShape s, int k);

// Poisson ratio fixed by the bond-based model: 1/4 (1D, 3D, plane strain), 1/3 (plane stress).
double bond_based_poisson(int dim, PlaneCondition plane);

struct PmbConstants {
  double c0;  // micromodulus peak (N/m^6 in 3D; per unit thickness/area folded in for 1D/2D)
  double s0;  // critical stretch
};

// c0 such that W_pd = W_classical for isotropic expansion. `thickness` is the 2D thickness or
// the 1D cross-section area (volumes carry it, so c0 divides it out).
double micromodulus_c0(int dim, PlaneCondition plane, InfluenceShape shape, double E, double delta,
                       double thickness);

// s0 such that breaking every bond across a unit crack area dissipates G0.
double critical_stretch_from_g0(int dim, InfluenceShape shape, double c0, double delta,
                                double thickness, double G0);

// Classical strain-energy density for isotropic expansion eps (the calibration state).
double classical_isotropic_energy(int dim, PlaneCondition plane, double E, double eps);

// P-wave modulus used for wave speeds (E in 1D).
double p_wave_modulus(int dim, PlaneCondition plane, double E, double nu);

std::string to_string(InfluenceShape s);

}  // namespace periadapt

#pragma once
// The constants of one material: moduli, density, fracture energy and what the force models
// derive from them at the deck's horizon (each node keeps its own micromodulus and critical
// stretch, scaled to its horizon).
#include <cmath>
#include <string>

#include "material/lps.hpp"
#include "material/micromodulus.hpp"

namespace periadapt {

struct MaterialLaw {
  std::string name = "material";
  double E = 0, nu = 0, rho = 0;
  double G0 = 0;                 // 0 when s0 was given directly
  double s0 = 0;
  double c0 = 0;
  double wave_speed = 0;         // P-wave speed for reports
  double thermal_strain = 0;     // alpha dT (PMB): bond stretch s - alpha dT
  InfluenceShape shape = InfluenceShape::Constant;
  PlaneCondition plane = PlaneCondition::None;
  double thickness = 1.0;
  LpsConstants lps_constants;  // the LPS formulation's moduli
  double onset_stretch = INFINITY;  // where a history law leaves its elastic branch
  // Young's modulus of the bond-based material with the same P-wave modulus: its micromodulus
  // (stored per node) drives the stable time step and the relaxation masses for both models.
  double bb_equivalent_E = 0;
  // Micromoduli divided by the quadrature's bulk lattice moment at each level's m
  // (discretization.micromodulus_calibration: lattice), so that every level has the bond
  // stiffness of the continuum and levels of different m meet without an impedance jump.
  bool lattice_calibration = false;
};

}  // namespace periadapt

#pragma once
// The Rayleigh (surface) wave speed of the deck's elastic constants: the speed a running crack
// tip cannot exceed in mode I (Freund's limit), against which a tracked tip's speed is read.
#include "material/micromodulus.hpp"

namespace periadapt {

// c_R from the root of the Rayleigh equation (2 - x^2)^2 = 4 sqrt(1 - k^2 x^2) sqrt(1 - x^2),
// x = c_R / c_s, k = c_s / c_p, with the in-plane c_p of the plane condition (plane stress:
// E / (1 - nu^2)). 0 in 1D, which has no surface wave.
double rayleigh_speed(int dim, PlaneCondition plane, double E, double nu, double rho);

}  // namespace periadapt

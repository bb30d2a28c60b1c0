#pragma once
// Bobaru et al. (2009) 6.2.2, Table IV: a half-Gaussian u0 = 0.02 exp(-0.01 x^2) at the free left
// end of a bar of length 450 (E = A = rho = 1, triangular micromodulus) splits and its right-going
// half (amplitude 0.01, speed 1) passes x = 400 at t = 400. Uniform grids of Table IV; arrival
// time and amplitude of the peak at x = 400 beside the published values, and fitted rates.
#include <string>

#include "core/node_set.hpp"

namespace periadapt {

struct WaveArrival {
  double time = 0, amplitude = 0;  // of the displacement peak at x = 400
  double mean_nodes = 0;           // active nodes averaged over the run
  std::size_t min_nodes = 0, max_nodes = 0;
};

// One grid of Table IV (uniform) or Table V (adaptive: level-1 refinement where the total energy
// density reaches 75% of its maximum, within 6 horizons, coarsening behind the pulse): `nodes`
// nodes on [0, 450], horizon `delta`.
// `scaling` (adaptive only): the AGRS horizon scaling of the refined zone, "delta" or "m".
// `lattice`: micromodulus_calibration: lattice (the quadrature's bond stiffness divided out).
WaveArrival bobaru_wave_arrival(int nodes, double delta, bool adaptive = false,
                                const std::string& scaling = "delta", bool lattice = false);

// u at x of a 1D bar: linear interpolation between the active nodes around x.
double bar_displacement_at(const NodeSet& nodes, double x);

int run_bobaru_1d_wave_study(const std::string& out_dir);

}  // namespace periadapt

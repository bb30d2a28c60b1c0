#pragma once
// Bobaru et al. (2009) 6.2.1, Table III: the half-Gaussian u0 = 0.02 exp(-0.01 x^2) at the free
// left end of a bar of length 300 (E = A = rho = 1) crosses a middle third [100, 200] with twice
// (case a) or four times (case b) the node density of the rest, at the same horizon 0.5. The
// interface at x = 200 reflects part of the pulse, which reaches the midpoint x = 150 at t = 250.
#include <string>

namespace periadapt {

struct DensityJumpReflection {
  double time = 0;       // of the reflected peak at x = 150 (parabola through the largest sample)
  double amplitude = 0;  // signed
  double modulus_coarse = 0, modulus_dense = 0;  // effective moduli of the two grids (E = 1)
};

// `density_factor` 1 (uniform coarse: the floor of the measure), 2 or 4; `shape` "constant" or
// "triangular"; `coarse_spacing` outside the middle third (0.2: the paper's 1,000 nodes on each
// outer third); `time_step` of the Velocity-Verlet integration.
// `dual_horizon`: bond_pairing dual_horizon (each bond pulls both ends alike: reciprocal across
// the jump); `lattice`: micromodulus_calibration: lattice (both grids get the continuum's bond
// stiffness).
DensityJumpReflection bobaru_density_jump(int density_factor, const std::string& shape,
                                          double coarse_spacing = 0.2, double time_step = 0.02,
                                          bool dual_horizon = false, bool lattice = false);

// `quick`: Table III's grids only, without the finer ones that show the reflection vanish.
int run_bobaru_density_jump_study(const std::string& out_dir, bool quick = false);

}  // namespace periadapt

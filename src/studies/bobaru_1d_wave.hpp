#pragma once
// Bobaru et al. (2009) 6.2.2, Table IV: a half-Gaussian u0 = 0.02 exp(-0.01 x^2) at the free left
// end of a bar of length 450 (E = A = rho = 1, triangular micromodulus) splits and its right-going
// half (amplitude 0.01, speed 1) passes x = 400 at t = 400. Uniform grids of Table IV; arrival
// time and amplitude of the peak at x = 400 beside the published values, and fitted rates.
#include <cmath>
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

// The largest peak of a sampled history u(t), refined by the parabola through the peak sample and
// its two neighbours. `magnitude`: peaks of |u| (either sign) instead of u.
struct PeakTracker {
  bool magnitude = false;
  double time = 0, value = 0;  // of the largest peak so far (value signed)
  // The sample u at time t (step dt); `armed`: whether a peak found now may count.
  void sample(double t, double u, double dt, bool armed = true) {
    auto key = [&](double v) { return magnitude ? std::abs(v) : v; };
    if (armed && key(prev_) > best_ && key(prev_) >= key(u) && key(prev_) >= key(prev2_)) {
      const double den = prev2_ - 2 * prev_ + u;
      const double off = den != 0 ? 0.5 * (prev2_ - u) / den : 0.0;
      best_ = key(prev_);
      time = t - dt + off * dt;
      value = prev_ - 0.25 * (prev2_ - u) * off;
    }
    prev2_ = prev_;
    prev_ = u;
  }

 private:
  double best_ = -1, prev_ = 0, prev2_ = 0;
};

// u at x of a 1D bar: linear interpolation between the active nodes around x.
double bar_displacement_at(const NodeSet& nodes, double x);

int run_bobaru_1d_wave_study(const std::string& out_dir);

}  // namespace periadapt

#pragma once
// Shared by the thesis 4.2 wave studies: a 2D linear wave run that records a probe history and
// each node's peak energy densities, and the comparison of a refined run with the uniform one.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "input/deck.hpp"
#include "input/deck_builder.hpp"

namespace periadapt {

struct WaveRun {
  std::vector<double> t, probe;  // u_x at the probe over time
  double e0 = 0, e_end = 0;      // total energy at the start and the end
  std::size_t nodes = 0;
  // Per active node at the end: position and the largest potential (W), kinetic (rho v^2 / 2) and
  // total (W + K) energy densities it reached during the run.
  std::vector<std::array<double, 2>> pos;
  std::vector<double> w_peak, k_peak, e_peak;
};

// The thesis' wave deck: a plane-stress strip [0, length] x [0, width] (E = rho = 1, m = 3,
// node-on-edge grid, PA-PDLAMMPS areas, no damage, dt = 1e-4) released from the Gaussian
// u_x = 2e-4 exp(-(x / width_of_pulse)^2).
DeckBuilder gaussian_wave_deck(double spacing, double length, double width, double width_of_pulse,
                               double end_time);

// Runs `deck` (explicit, 2D) and records u_x at the active node nearest
// `probe`.
WaveRun run_wave(const Deck& deck, std::array<double, 2> probe);

// Drop (%) of each refined node's peak density below the uniform run's at the nearest node of
// the uniform grid (node_on_edge, spacing dx, nx nodes per row), over the nodes `inside` selects:
// {largest drop, smallest drop}. `which` picks w_peak, k_peak or e_peak.
std::array<double, 2> peak_drops(const WaveRun& refined, const WaveRun& uniform, double dx, long nx,
                                 const std::function<bool(double, double)>& inside,
                                 std::vector<double> WaveRun::*which);

// Largest |u_refined - u_uniform| at the probe in % of the uniform run's largest |u| there.
double reflection_percent(const WaveRun& refined, const WaveRun& uniform);

}  // namespace periadapt

#pragma once
// Thesis 4.2 (models A-C): the Gaussian wave of examples/gaussian_wave_2d.yaml crossing a small
// level-1 patch at the plate centre (dX 0.5 -> 0.25 mm, no visibility widening): A keeps the
// horizon (m-convergence, m = 6 in the patch), B halves it (delta-convergence, m = 3), C is B with
// the interface-horizon correction. Reported against the uniform coarse run: the change of total
// energy over the run (Delta E_tot) and the largest displacement difference at a probe before
// the patch relative to the incident amplitude (the reflection, Delta u), and the largest and
// smallest drop of a patch node's peak potential (Delta W) and kinetic (Delta K) energy density
// below the uniform run's at the nearest coarse node; thesis Table 4.3.
#include <array>
#include <string>
#include <vector>

#include "io/line_plot.hpp"

namespace periadapt {

struct WavePatchRow {
  std::string name;
  std::size_t nodes;
  double energy_change;         // |E_end / E_0 - 1| in %
  double reflection;            // Delta u in % of the incident amplitude (0 for the uniform run)
  std::array<double, 2> w_drop;  // Delta W max, min (%)
  std::array<double, 2> k_drop;  // Delta K max, min (%)
};

// The uniform coarse run, then models A, B, C; probe histories appended to `series` if given.
std::vector<WavePatchRow> wave_patch_rows(std::vector<PlotSeries>* series = nullptr);

int run_wave_patch_study(const std::string& out_dir);

}  // namespace periadapt

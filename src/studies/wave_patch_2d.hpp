#pragma once
// Thesis 4.2 (models A-C): the Gaussian wave of examples/gaussian_wave_2d.yaml crossing a small
// level-1 patch at the plate centre (dX 0.5 -> 0.25 mm, no visibility widening): A keeps the
// horizon (m-convergence, m = 6 in the patch), B halves it (delta-convergence, m = 3), C is B with
// the interface-horizon correction. Reported against the uniform coarse run: the change of total
// energy over the run (Delta E_tot) and the largest displacement difference at a probe before
// the patch relative to the incident amplitude (the reflection, Delta u); thesis Table 4.3.
#include <string>

namespace periadapt {

int run_wave_patch_study(const std::string& out_dir);

}  // namespace periadapt

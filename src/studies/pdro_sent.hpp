#pragma once
// Stewart & Jeon 2019, section 3.2 (Fig. 8): single-edge-notched tension under a stress ramp.
// Runs examples/pdro_sent_2d.yaml on native grids and on its own grid with the refinement
// overlay, and prints the remote stress at failure (the tip 5 mm ahead of the notch) beside the
// LEFM value of Eqs. 11-12, sigma_f = K_IC / (sqrt(W) f(a/W)) with the plane-strain K_IC of G0.
#include <string>
#include <vector>

namespace periadapt {

struct PdroSentOptions {
  std::string deck = "examples/pdro_sent_2d.yaml";
  std::vector<double> native_spacings{1.0e-3, 0.7e-3, 0.5e-3};
  std::vector<double> overlay_n{1.0 / 0.7, 2.0, 5.0};
  bool pim = false;
  bool gaussian = false;  // PDDO weight: Gaussian instead of uniform
  bool whole_bond = false;  // overlay sub-pairs over the whole bond instead of the paper's three
};

// LEFM failure stress of an edge crack a in a strip of width W (Eqs. 11-12).
double sent_lefm_failure_stress(double E, double nu, double G0, double a, double W);

int run_pdro_sent_study(const std::string& out_dir, const PdroSentOptions& opt);

}  // namespace periadapt

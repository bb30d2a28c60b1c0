#pragma once
// Stewart & Jeon 2019, section 3.1 (Figs. 5-6): a 2D plane-strain bar, 200 mm long, pulled from
// both ends; the remote strain at failure of native grids dx' = 0.1 ... 0.9 mm (m = 4) against a
// 1 mm grid with the refinement overlay at n = dx/dx', both beside the analytic critical stretch
// of Eq. 2, s0 = sqrt(5 pi G0 / (12 E delta)) (E = 72 GPa, rho = 2400 kg/m^3, G0 = 6 J/m^2).
// The bar starts with the homogeneous velocity field of the pull (v = +-v_end at the ends,
// linear in between) and the grip layers (one horizon wide) keep following it, so no start-up
// wave travels and the end speed can be raised above the paper's 50 mm/s to keep the fine grids
// affordable; failure = the peak of the end load.
#include <string>
#include <vector>

namespace periadapt {

struct PdroBarOptions {
  double length = 0.2, width = 8e-3;
  double end_speed = 5.0;  // m/s at each end
  std::vector<double> targets{0.9e-3, 0.8e-3, 0.7e-3, 0.6e-3, 0.5e-3,
                              0.4e-3, 0.3e-3, 0.2e-3, 0.1e-3};  // dx' (m)
  double coarse = 1e-3;
  bool pim = false;       // overlay interpolation: PIM instead of PDDO
  bool gaussian = false;  // PDDO weight: Gaussian instead of uniform
  bool whole_bond = false;  // overlay sub-pairs over the whole bond instead of the paper's three
};

struct PdroBarRow {
  double target = 0, n = 0, s0_eq2 = 0;
  double native_strain = 0, overlay_strain = 0;  // remote strain at the peak end load
  double overlay_check_fraction = 0;             // overlay checks / bond evaluations
};

// Runs the native and overlay bars for every target; prints nothing.
std::vector<PdroBarRow> pdro_bar_rows(const PdroBarOptions& opt);

// The study command: table and, with out_dir, a PNG and CSV of failure strain vs dx'.
int run_pdro_bar_study(const std::string& out_dir, const PdroBarOptions& opt);

}  // namespace periadapt

#pragma once
// Thesis 4.1, models A-C: the static plate of the uniform study with its left half refined to
// level 1, 2 or 3 (method B, delta-scaling, m = 3.015, visibility criterion), solved with plain
// scaling (source-horizon micromodulus), with dual horizons, and with dual horizons plus surface
// correction. Prints peak and plateau errors of u_x on the horizontal centre line beside the
// thesis' values; writes CSV and one PNG per model.
#include <string>

namespace periadapt {

int run_static_plate_refined_study(const std::string& out_dir);

// Models D-F: the upper half refined instead (Figs. 4.12-4.21). Prints the peak and plateau
// errors of u_y on the vertical centre line on each side, and u_x along x = 0.2 m on each side.
int run_static_plate_upper_study(const std::string& out_dir);

}  // namespace periadapt

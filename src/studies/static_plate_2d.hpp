#pragma once
// Thesis 4.1 on the uniform grid: the static plate in uniaxial tension (1 m x 0.5 m x 0.01 m,
// 200 MPa, E = 200 GPa, nu = 1/3 plane stress, dX = 10 mm, delta = 30.15 mm, IPA-Hybrid areas,
// symmetry constraints of Fig. 4.1), solved with and without surface correction. Relative errors
// of u_x along the horizontal and of u_y along the vertical centre line against Eq. 4.1, and the
// L2 error of Eq. 4.2; CSV and PNG of the profiles.
#include <string>

namespace periadapt {

int run_static_plate_study(const std::string& out_dir);

}  // namespace periadapt

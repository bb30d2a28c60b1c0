#pragma once
// Thesis 5.2: the bond directions of a regular 2D grid are the "weak" directions along which a
// crack cuts fewer bonds than along neighbouring directions, so cracks on coarse grids follow
// them. The set depends on m = delta / dX and on which cells the quadrature keeps in a family
// (PA-PDLAMMPS: nodes within the horizon; IPA-Hybrid: also cells only partly covered). Computed
// here from the family of an interior node of an actual model.
#include <string>
#include <vector>

namespace periadapt {

// Distinct bond directions in degrees within [0, 90] (the grid's symmetry gives the rest) of an
// interior node for horizon factor m and `quadrature` (a deck value: pa_pdlammps, ipa_hybrid,
// subcell, full).
std::vector<double> weak_directions_deg(double m, const std::string& quadrature);

// Prints the directions for the thesis' m (2.51, 3) and a few larger ones, per quadrature.
int run_weak_directions_study(const std::string& out_dir);

}  // namespace periadapt

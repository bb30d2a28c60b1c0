#pragma once
// Errors of a solved plate in uniaxial tension against the classical field (thesis Eq. 4.1:
// u_x = p x / E, u_y = -nu p y / E) along the centre lines and in the L2 norm (Eq. 4.2).
// A node belongs to the horizontal (vertical) centre line when |y| (|x|) is at most half its
// spacing: refined zones of method B have no node on the axis itself.
#include <string>
#include <vector>

#include "core/node_set.hpp"
#include "input/deck.hpp"

namespace periadapt {

struct PlateErrors {
  std::vector<double> x, ex;  // horizontal line: x and |e(u_x)| in %, x != 0, sorted
  std::vector<double> y, ey;  // vertical line: y and |e(u_y)| in %, y != 0, sorted
  double l2 = 0;              // Eq. 4.2, in %
  // Mean and largest |e(u_x)| over x in [lo, hi] (%), and of |e(u_y)| over y in [lo, hi].
  double mean_ex(double lo, double hi) const;
  double max_ex(double lo, double hi) const;
  double mean_ey(double lo, double hi) const;
  double max_ey(double lo, double hi) const;
};

PlateErrors plate_errors(const NodeSet& nodes, double p, double E, double nu);

// The deck of thesis 4.1 (Fig. 4.1): 1 m x 0.5 m x 0.01 m, 200 MPa on both short edges,
// E = 200 GPa, nu = 1/3 plane stress, dX = 10 mm, delta = 30.15 mm, node-on-edge grid with the
// symmetry-axis constraints, IPA-Hybrid areas; `refined_level` > 0 refines a half to that level:
// x < 0 (models A-C) or y > 0 (`upper_half`, models D-F).
// `surface_correction`: the deck value (false | energy | moments).
Deck tension_plate_deck(const std::string& surface_correction, const std::string& bond_pairing,
                        int refined_level, bool upper_half = false,
                        const std::string& name = "tension plate (built-in)");

}  // namespace periadapt

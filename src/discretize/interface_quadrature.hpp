#pragma once
// Level interfaces and the patch test. A node whose horizon holds cells of two sizes sums its
// bonds with a midpoint rule that does not integrate the bond force of a linear displacement
// field exactly, so a uniform strain pulls it (ghost forces; bench/interface/patch_test.sh).
// For bond-based forces f_i = c_i sum_j w_j s_j e_j, s_j = e_j . eps e_j, with w_j = g beta_j V_j,
// the force of every uniform strain vanishes exactly when the third moments
//   T_pqr = sum_j w_j e_p e_q e_r
// do. The fit scales each interface bond by 1 + sum_m lambda_m phi_m(e), phi the cubic monomials
// of the bond direction (4 in 2D, 10 in 3D, 1 in 1D), with lambda solving the Gram system that
// zeroes T. A complete family on one lattice has T = 0 by symmetry and is left alone; so is a
// node whose family misses volume (a free surface, a crack face or a hole within its horizon),
// where a uniform strain does pull the body and the surface correction is the tool.
#include <cstddef>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "material/micromodulus.hpp"

namespace periadapt {

struct InterfaceFitStats {
  std::size_t interface_rows = 0;  // rows with bonds to cells of another size
  std::size_t fitted = 0;          // rows whose bonds were scaled
  std::size_t incomplete = 0;      // interface rows left alone: their family misses volume
  std::size_t refused = 0;         // fits that would scale a bond outside [1/2, 3/2]
};

// Fits the rows flagged in `rows` (all rows when empty).
InterfaceFitStats fit_interface_quadrature(const NodeSet& ns, BondFamilies& bf,
                                           InfluenceShape shape,
                                           const std::vector<char>& rows = {});

// Per row of `rows`: whether the nodes' cells cover the row's horizon ball (sampled on rings at
// 0.5, 0.8 and 0.98 of the horizon); false where a free surface, hole or body edge lies within it.
std::vector<char> rows_with_covered_ball(const NodeSet& ns, const std::vector<std::uint32_t>& rows);

}  // namespace periadapt

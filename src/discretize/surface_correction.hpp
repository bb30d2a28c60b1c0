#pragma once
// Surface correction: per-bond factors that give nodes near free surfaces (and, on coarse
// lattices, every node) the bulk continuum strain-energy density. They multiply the bond's
// quadrature factor. Two methods:
//
// Energy (Madenci & Oterkus 2014, used in thesis 4.1): for every node and axis d, the
// peridynamic strain-energy density under a uniaxial strain along d is compared with the
// classical one, g_d(i) = W_classical / W_pd(i); a bond takes the mean of its two ends per axis
// and combines the axes along its direction n as
//   G_ij = ( sum_d (n_d / gbar_d)^2 )^(-1/2),   gbar_d = (g_d(i) + g_d(j)) / 2.
// It fixes the axial stiffnesses only: the coupling between axes (what sets the Poisson
// contraction) stays as the truncated family or the lattice leaves it.
//
// Moments: the bond factors are made such that every node's fourth-order bond moments
// sum_j w n_a n_a n_b n_b equal the isotropic bulk ones. The strain-energy density of a
// homogeneous strain is a quadratic form with exactly these moments as coefficients (for families
// symmetric about the axes), so the node then has the classical energy for every homogeneous
// strain, shear and biaxial alike, not only the axial ones. Each sweep fits every node's own
// direction multiplier G_i(n) = sum_d a_d n_d^2 + sum_{d<e} b_de n_d^2 n_e^2 (bulk: G = 1) to its
// current moments and multiplies each bond by (G_i(n) G_j(n))^(omega/2), until no bond changes.
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "discretize/families.hpp"
#include "material/micromodulus.hpp"

namespace periadapt {

enum class SurfaceCorrection { None, Energy, Moments };

// Held bond rows (a distributed set-up, parallel/held_rows.hpp): a rank holds some rows only, so
// the per-node values a correction computes from a row (g, the multipliers) come from the row's
// owner, and a sweep's largest change is the largest over the ranks.
struct HeldRowsShare {
  std::function<void(std::vector<double>& values, int per_node)> owners;
  std::function<double(double)> max;
};

// `uniaxial_modulus`: the classical modulus M with W = M eps^2 / 2 under uniaxial strain
// (P-wave modulus of the dimension and plane condition). 1D models use the energy method (both
// methods coincide there). `state_based` (LPS): the moments method makes the moments of the
// weighted volume (w x^2 V) isotropic relative to m instead of matching the bond-based energy,
// which gives the LPS node the exact dilatation and the classical energy of every homogeneous
// strain; the energy method is the bond-based one either way. `block_modulus`: with several
// materials, the uniaxial modulus of each block (node i's is block_modulus[nodes.block[i]]).
void apply_surface_correction(const NodeSet& nodes, BondFamilies& bonds, InfluenceShape shape,
                              double uniaxial_modulus,
                              SurfaceCorrection method = SurfaceCorrection::Energy,
                              bool state_based = false,
                              const std::vector<double>& block_modulus = {},
                              const HeldRowsShare* held = nullptr);

// After a refinement event: the rows flagged in `fresh` were searched again (their factors are the
// quadrature's), every other row keeps its corrected factors. Corrects the fresh rows and the
// bonds the rows around them hold, so that the cost follows the event's window, not the model:
// - energy: the nodes next to the window get their g from a search of their rows, so every bond
//   ends with the factor a correction of the whole model gives;
// - moments: the window and the ring next to it fit their multipliers again from their
//   quadrature factors on the bonds between them (bonds to nodes beyond keep theirs, and so do
//   those nodes' moments); the fixed point is not unique, so the factors differ a little from a
//   correction from scratch (row stiffness sums within 1%) while every fitted node meets the
//   bulk moments.
// Returns the rows outside `fresh` whose bonds changed.
std::vector<std::uint32_t> correct_surface_window(
    const NodeSet& nodes, BondFamilies& bonds, const QuadratureSpec& quadrature,
    InfluenceShape shape, double uniaxial_modulus, SurfaceCorrection method, bool state_based,
    const std::vector<double>& block_modulus, const std::vector<char>& fresh);

}  // namespace periadapt

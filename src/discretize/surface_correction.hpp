#pragma once
// Surface correction by the energy method (Madenci & Oterkus 2014, used in thesis 4.1): for every
// node and axis d, the peridynamic strain-energy density under a uniaxial strain along d is
// compared with the classical one, g_d(i) = W_classical / W_pd(i); a bond takes the mean of its
// two ends per axis and combines the axes along its direction n as
//   G_ij = ( sum_d (n_d / gbar_d)^2 )^(-1/2),   gbar_d = (g_d(i) + g_d(j)) / 2,
// which multiplies the bond's quadrature factor. Away from surfaces it also absorbs the
// quadrature's own energy error (e.g. the PA-PDLAMMPS deficit).
#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "material/micromodulus.hpp"

namespace periadapt {

// `uniaxial_modulus`: the classical modulus M with W = M eps^2 / 2 under uniaxial strain
// (P-wave modulus of the dimension and plane condition).
void apply_surface_correction(const NodeSet& nodes, BondFamilies& bonds, InfluenceShape shape,
                              double uniaxial_modulus);

}  // namespace periadapt

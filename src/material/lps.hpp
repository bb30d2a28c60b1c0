#pragma once
// Ordinary state-based peridynamics, the linear peridynamic solid (LPS; Silling et al. 2007; thesis
// 2.1, Eqs. 2.5-2.10), for 3D and 2D plane stress / plane strain with any Poisson ratio:
//   m_i     = sum_j w x^2 beta V_j                                 (weighted volume, Eq. 2.9)
//   theta_i = (D / m_i) sum_j w x e beta V_j,  e = |Y| - x           (dilatation, D = 2 or 3)
//   t_ij    = (D kappa theta_i / m_i) w x + (alpha / m_i) w (e - theta_i x / D)
//   f_i     = sum_j (t_ij beta_ij + t_ji beta_ji) V_j Y/|Y|
// with every sum over the bonds whose far end's family holds the near end too, and beta_ij the
// quadrature factor of j in i's family. On a uniform grid that is every bond, and beta_ij =
// beta_ji. On a refined one a coarse family reaches fine nodes whose horizons do not reach back:
// such a bond would act on one end only (t_ij with no reaction on j, or a t_ji of a state that
// does not contain the bond) and feed energy in without bound. Over the mutual bonds the pair
// force appears in both rows, and with each end's own factor (a fine horizon cuts a coarse cell
// that the coarse horizon holds whole) it is the gradient of sum V_i W_i: momentum and energy
// are conserved (BondFamilies::reverse_beta holds the far ends' factors at level interfaces).
// LPS normalizes each state by its weighted volume, so a coarse node that loses a few far bonds
// keeps the calibrated response.
// with 3D: kappa = K, alpha = 15 mu; 2D: kappa = the in-plane bulk modulus (plane strain
// E / (2 (1 + nu)(1 - 2 nu)), plane stress E / (2 (1 - nu))), alpha = 8 mu. With this 2D
// dilatation the deviatoric part is orthogonal to x, so the force state needs no extra term (the
// thesis' Eq. 2.10 sign question does not arise); the calibration is checked against classical
// energy densities in the tests. w = influence shape of the source node's horizon; a bond breaks
// when e / x exceeds the source node's critical stretch.
#include <cstdint>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "material/micromodulus.hpp"
#include "overlay/pdro.hpp"

namespace periadapt {

struct LpsConstants {
  double kappa = 0;  // bulk modulus of the dimension/plane condition
  double mu = 0;     // shear modulus
  int D = 3;         // 2 or 3: dilatation factor
  double alpha = 15; // 15 (3D) or 8 (2D)
};

LpsConstants lps_constants(int dim, PlaneCondition plane, double E, double nu);

// Critical stretch for a fracture energy G0 (Madenci & Oterkus 2014, OSB with w = 1):
// 3D s0 = sqrt(G0 / ((3 mu + (3/4)^4 (K - 5 mu / 3)) delta)),
// 2D s0 = sqrt(G0 / ((6 mu / pi + 16 / (9 pi^2) (kappa - 2 mu)) delta)).
double lps_critical_stretch(int dim, const LpsConstants& c, double delta, double G0);

// Per-node scratch of the two-pass kernel.
struct LpsScratch {
  std::vector<double> m, theta;
  // Longest bond of each family: node i lies in j's family exactly when |xi_ij| <= reach_j (a
  // family holds every node within its search radius).
  std::vector<double> reach;
  // Packed per node for the force pass: [D kappa theta / m, alpha mu / m, theta / D, 1/delta].
  std::vector<double> packed;
  // Several materials (material/blocks.hpp; empty for one): each block's constants, so a node's
  // state uses its own block's moduli, and the pair table inv_stretch of the blocks (a bond from
  // block a to b breaks when its stretch times block_inv_stretch[a * count + b] exceeds s0_i).
  std::vector<LpsConstants> block_constants;
  std::vector<double> block_inv_stretch;
};

// The constants of node i's state.
inline const LpsConstants& node_constants(const LpsConstants& c, const LpsScratch& sc,
                                          const NodeSet& ns, std::size_t i) {
  return sc.block_constants.empty() ? c : sc.block_constants[ns.block[i]];
}

// Force densities (and bond breaking, broken-bond log, energy density, refinement overlay as
// for PMB). `rows`: the forces (and W) of these nodes only (W of the others is 0), from the
// dilatations of `dilatation_rows` (null: every node; it must hold `rows` and their neighbours).
// `breakable_stretch`: also the largest stretch of each computed row's intact breakable bonds
// after the pass (the stretch trigger's measure), as for PMB.
std::size_t lps_forces(NodeSet& nodes, BondFamilies& bonds, InfluenceShape shape,
                       const LpsConstants& c, bool allow_breaking, LpsScratch& scratch,
                       std::vector<std::uint64_t>* broken_log, std::vector<double>* W,
                       const PdroSpec* pdro = nullptr,
                       const std::vector<std::uint32_t>* rows = nullptr,
                       const std::vector<std::uint32_t>* dilatation_rows = nullptr,
                       std::vector<double>* breakable_stretch = nullptr);

// Weighted volume and dilatation of every active node into `scratch` (the first pass).
// `mutual_only`: over the mutual bonds, as the plain kernel's states (above); false: over whole
// families (the dual-horizon form). `rows`: these nodes' only (the others keep 0).
void lps_dilatation(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                    const LpsConstants& c, LpsScratch& scratch, bool mutual_only,
                    const std::vector<std::uint32_t>* rows = nullptr);

// Strain-energy density W_i = kappa theta^2 / 2 + (alpha mu / (2 m)) sum w (e^d)^2 beta V.
// `rows`: these nodes' only (the others keep theirs).
void lps_energy_density(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                        const LpsConstants& c, LpsScratch& scratch, std::vector<double>& W,
                        bool mutual_only, const std::vector<std::uint32_t>* rows = nullptr);

// Stress of every node, sigma_i = dW_i / d(eps) = sum_j t_ij e_ij (x) xi_ij beta V_j over the
// intact bonds of its state (the classical stress of a homogeneous strain where W_i is
// classical); the dilatation is left in scratch.theta. Row-major 3 x 3 per node.
void lps_stress(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                const LpsConstants& c, LpsScratch& scratch, std::vector<double>& sigma,
                bool mutual_only);

}  // namespace periadapt

#pragma once
// The one dispatch point from a Formulation to its kernels: the material's forces (all rows,
// given rows, or a distributed pass's share), energy density and stress, and how its breaking
// stretch follows the horizon. Solvers, the adaptor and setup reach PMB, LPS and the registered
// history laws through these, never through a kernel.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "material/blocks.hpp"
#include "material/dual_rows.hpp"
#include "material/formulation.hpp"
#include "material/lps.hpp"
#include "material/material_law.hpp"
#include "overlay/pdro.hpp"

namespace periadapt {

// What the kernels read besides the nodes and bonds.
struct MaterialContext {
  const Formulation& formulation;
  const MaterialLaw& material;  // the base law (each node keeps its own c and s0)
  LpsScratch& lps;             // LPS weighted volumes and dilatations
  const PdroSpec* pdro = nullptr;
  const BlockPairs* blocks = nullptr;
};

// One force pass.
struct ForcePass {
  bool allow_breaking = false;
  std::vector<std::uint64_t>* broken_log = nullptr;  // bonds broken by this pass
  std::vector<double>* W = nullptr;                  // energy densities from the same sweep
  // Only these rows (the others keep theirs): a row-local formulation, or a distributed
  // source-horizon pass. Null: every row.
  const std::vector<std::uint32_t>* rows = nullptr;
  // LPS with `rows`: the rows whose dilatations the forces of `rows` read.
  const std::vector<std::uint32_t>* dilatation_rows = nullptr;
  std::vector<double>* breakable_stretch = nullptr;  // the stretch trigger's measure per row
  const DualRows* split = nullptr;  // dual-horizon pairing: a distributed pass's share
};

// Forces into nodes.f; breaks bonds when allowed; returns the number broken.
std::size_t material_forces(NodeSet& nodes, BondFamilies& bonds, const MaterialContext& ctx,
                            const ForcePass& pass);
// Stored (recoverable) strain-energy density of every node, or of `rows` only (the others keep
// theirs).
void material_energy_density(const NodeSet& nodes, const BondFamilies& bonds,
                             const MaterialContext& ctx, std::vector<double>& W,
                             const std::vector<std::uint32_t>* rows = nullptr);
// Stress of every node, the derivative of its energy density with respect to a homogeneous
// strain (row-major 3 x 3 per node; LPS also leaves the dilatation in ctx.lps.theta).
void material_stress(const NodeSet& nodes, const BondFamilies& bonds, const MaterialContext& ctx,
                     std::vector<double>& sigma);

// The stiffness sum sum_j c_i g beta_j V_j / xi of each row (node i): the Silling-Askari
// stable-step bound and the relaxation's fictitious masses. For every formulation it is the
// elastic bond-based material's of the same P-wave modulus, whose micromodulus each node keeps.
void material_stiffness_sum(const NodeSet& nodes, const BondFamilies& bonds,
                            const MaterialContext& ctx, std::vector<double>& K);
double material_stiffness_row(const NodeSet& nodes, const BondFamilies& bonds,
                              const MaterialContext& ctx, std::size_t i);

// The static solve's tangent (formulation.bond_based(): PMB, and the history laws on their
// elastic branch): intact bond k of row i is a spring c_i g(|xi|/delta_i) beta / |xi| along its
// direction, times the far end's volume (the assembly's), scaled across blocks.
inline double elastic_bond_stiffness(const NodeSet& ns, const BondFamilies& bf,
                                     InfluenceShape shape, const BlockPairs* pairs, std::size_t i,
                                     std::uint64_t k) {
  const double L = bf.length(k);
  double w = ns.micromodulus[i] * influence(shape, std::min(1.0, L / ns.horizon[i])) *
             static_cast<double>(bf.beta[k]) / L;
  if (pairs && pairs->active()) w *= pairs->stiffness_row(ns.block[i])[ns.block[bf.neighbor[k]]];
  return w;
}

// The critical stretch of a brittle bond of this formulation at horizon delta (micromodulus
// constant c0 there) that dissipates mat.G0 over a crack.
double brittle_critical_stretch(const Formulation& f, int dim, const MaterialLaw& mat, double c0,
                                double delta);
// The stretch at which a bond breaks: the brittle one, or a history law's from it and its
// onset (a stress, the same at every horizon), so that a crack still dissipates G0.
double breaking_stretch(const Formulation& f, int dim, const MaterialLaw& mat, double c0,
                        double delta);

}  // namespace periadapt

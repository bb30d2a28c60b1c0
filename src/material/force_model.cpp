#include "material/force_model.hpp"

#include "material/lps_dual.hpp"
#include "material/pmb.hpp"
#include "material/pmb_dual.hpp"

namespace periadapt {

namespace {

using Kind = Formulation::Kind;

BondLawCall law_call(const MaterialContext& ctx, const ForcePass& p = {}) {
  BondLawCall c;
  c.shape = ctx.material.shape;
  c.onset_stretch = ctx.material.onset_stretch;
  c.allow_breaking = p.allow_breaking;
  c.broken_log = p.broken_log;
  c.W = p.W;
  c.rows = p.rows;
  c.breakable_stretch = p.breakable_stretch;
  c.split = p.split;
  return c;
}

}  // namespace

std::size_t material_forces(NodeSet& nodes, BondFamilies& bonds, const MaterialContext& ctx,
                            const ForcePass& p) {
  const Formulation& f = ctx.formulation;
  const MaterialLaw& mat = ctx.material;
  const DualRows whole;
  const DualRows& split = p.split ? *p.split : whole;
  switch (f.kind) {
    case Kind::HistoryLaw:
      return f.dual_horizon ? f.law->dual_forces(nodes, bonds, law_call(ctx, p))
                            : f.law->forces(nodes, bonds, law_call(ctx, p));
    case Kind::Lps:
      return f.dual_horizon
                 ? lps_dual_forces(nodes, bonds, mat.shape, mat.lps_constants, p.allow_breaking,
                                   ctx.lps, p.broken_log, p.W, split)
                 : lps_forces(nodes, bonds, mat.shape, mat.lps_constants, p.allow_breaking,
                              ctx.lps, p.broken_log, p.W, ctx.pdro, p.rows, p.dilatation_rows,
                              p.breakable_stretch);
    case Kind::Pmb:
      return f.dual_horizon
                 ? pmb_dual_forces(nodes, bonds, mat.shape, p.allow_breaking, p.broken_log, p.W,
                                   split)
                 : pmb_forces(nodes, bonds, mat.shape, p.allow_breaking, p.broken_log, p.W,
                              ctx.pdro, mat.thermal_strain, p.rows, p.breakable_stretch,
                              ctx.blocks)
                       .newly_broken;
  }
  return 0;
}

void material_energy_density(const NodeSet& nodes, const BondFamilies& bonds,
                             const MaterialContext& ctx, std::vector<double>& W,
                             const std::vector<std::uint32_t>* rows) {
  const Formulation& f = ctx.formulation;
  const MaterialLaw& mat = ctx.material;
  switch (f.kind) {
    case Kind::HistoryLaw: {
      ForcePass p;
      p.rows = rows;
      f.law->energy_density(nodes, bonds, law_call(ctx, p), W);
      return;
    }
    case Kind::Lps:
      lps_energy_density(nodes, bonds, mat.shape, mat.lps_constants, ctx.lps, W,
                         !f.dual_horizon, rows);
      return;
    case Kind::Pmb:
      pmb_energy_density(nodes, bonds, mat.shape, W, mat.thermal_strain, rows, ctx.blocks);
      return;
  }
}

void material_stress(const NodeSet& nodes, const BondFamilies& bonds, const MaterialContext& ctx,
                     std::vector<double>& sigma) {
  const Formulation& f = ctx.formulation;
  const MaterialLaw& mat = ctx.material;
  switch (f.kind) {
    case Kind::HistoryLaw:
      f.law->stress(nodes, bonds, law_call(ctx), sigma);
      return;
    case Kind::Lps:
      lps_stress(nodes, bonds, mat.shape, mat.lps_constants, ctx.lps, sigma, !f.dual_horizon);
      return;
    case Kind::Pmb:
      pmb_stress(nodes, bonds, mat.shape, sigma, mat.thermal_strain, ctx.blocks);
      return;
  }
}

void material_stiffness_sum(const NodeSet& nodes, const BondFamilies& bonds,
                            const MaterialContext& ctx, std::vector<double>& K) {
  pmb_stiffness_sum(nodes, bonds, ctx.material.shape, K, ctx.blocks);
}

double material_stiffness_row(const NodeSet& nodes, const BondFamilies& bonds,
                              const MaterialContext& ctx, std::size_t i) {
  return pmb_stiffness_row(nodes, bonds, ctx.material.shape, i, ctx.blocks);
}

double brittle_critical_stretch(const Formulation& f, int dim, const MaterialLaw& mat, double c0,
                                double delta) {
  return f.state_based()
             ? lps_critical_stretch(dim, mat.lps_constants, delta, mat.G0)
             : critical_stretch_from_g0(dim, mat.shape, c0, delta, mat.thickness, mat.G0);
}

double breaking_stretch(const Formulation& f, int dim, const MaterialLaw& mat, double c0,
                        double delta) {
  const double sb = brittle_critical_stretch(f, dim, mat, c0, delta);
  return f.keeps_bond_history() ? f.law->breaking_stretch(sb, mat.onset_stretch) : sb;
}

}  // namespace periadapt

#include "setup/build_model.hpp"

#include "adapt/refine.hpp"
#include "adapt/setup_zones.hpp"
#include "discretize/surface_correction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include <cmath>

#include "core/expression.hpp"
#include "discretize/families.hpp"
#include "input/deck_error.hpp"
#include "material/force_model.hpp"
#include "parallel/held_rows.hpp"
#include "parallel/mpi_env.hpp"
#include "setup/memory_estimate.hpp"

namespace periadapt {

namespace {

std::vector<std::uint32_t> select(const NodeSet& ns, const Shape& region, double tol) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (region.contains({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, tol))
      out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

// The laws of the deck's blocks ([0]: the material section's), the rules of the bonds between
// them, and each node's block (the last block whose region holds it).
void assign_blocks(const Deck& dk, Model& m, double tol) {
  const MaterialLaw& base = m.material;
  const bool lps = m.formulation.state_based();
  m.block_materials.assign(1, base);
  for (const BlockSpec& b : dk.blocks) {
    MaterialLaw law = base;
    law.name = b.name;
    law.E = b.E;
    law.rho = b.rho;
    law.bb_equivalent_E = b.E;
    if (lps) {
      law.nu = *b.nu;
      law.lps_constants = lps_constants(dk.dim, dk.plane, b.E, law.nu);
      law.bb_equivalent_E = p_wave_modulus(dk.dim, dk.plane, b.E, law.nu) /
                            p_wave_modulus(dk.dim, dk.plane, 1.0, bond_based_poisson(dk.dim, dk.plane));
    }
    law.c0 = micromodulus_c0(dk.dim, dk.plane, dk.shape, law.bb_equivalent_E, dk.horizon, dk.thickness);
    law.G0 = b.G0.value_or(0.0);
    law.s0 = b.G0 ? breaking_stretch(m.formulation, dk.dim, law, law.c0, dk.horizon) : b.s0.value_or(INFINITY);
    law.wave_speed = std::sqrt(p_wave_modulus(dk.dim, dk.plane, b.E, law.nu) / b.rho);
    m.block_materials.push_back(std::move(law));
  }
  m.block_pairs = block_pair_rules(m.block_materials, dk.dim, lps, dk.horizon);
  if (lps) {
    for (const MaterialLaw& law : m.block_materials)
      m.lps_scratch.block_constants.push_back(law.lps_constants);
    m.lps_scratch.block_inv_stretch = m.block_pairs.inv_stretch;
  }
  NodeSet& ns = m.nodes;
  ns.block.assign(ns.size(), 0);
  for (std::size_t r = 0; r < dk.blocks.size(); ++r) {
    const std::vector<std::uint32_t> nodes = select(ns, dk.blocks[r].region, tol);
    if (nodes.empty())
      throw DeckError(dk.file, dk.blocks[r].line, dk.blocks[r].column,
                      "blocks[" + std::to_string(r) + "].region",
                      "the region selects no nodes (a node belongs to a block when its cell "
                      "centre lies inside the region)");
    for (std::uint32_t i : nodes) ns.block[i] = static_cast<std::uint8_t>(r + 1);
  }
}

}  // namespace

Model build_model(const Deck& dk, const FamilyBuild& families) {
  Model m;
  NodeSet& ns = m.nodes;
  ns.dim = dk.dim;
  m.grid_spacing = dk.grid.spacing;
  m.horizon = dk.horizon;
  check_memory_estimate(dk);  // before any allocation
  std::vector<std::size_t> removed_by_hole;
  generate_grid(dk.grid, ns, &removed_by_hole);
  if (ns.size() == 0)
    throw DeckError(dk.file, 0, 0, "discretization", "the grid has no nodes inside the body");
  // A hole that removes no grid point leaves the body as if it were not there (refined zones
  // would then open it where they cut it, and nowhere else).
  for (std::size_t k = 0; k < removed_by_hole.size(); ++k)
    if (removed_by_hole[k] == 0)
      throw DeckError(dk.file,
                      k < dk.holes_at.size() ? dk.holes_at[k]
                                             : DeckPlace{"discretization.holes[" + std::to_string(k) + "]"},
                      fmt::format("the hole removes no node: it lies outside the body, inside "
                                  "another hole, or between the grid points (spacing {:g} m); "
                                  "a hole must contain at least one grid point",
                                  dk.grid.spacing));

  MaterialLaw& mat = m.material;
  mat.name = dk.material_name;
  mat.E = dk.E;
  mat.rho = dk.rho;
  mat.nu = bond_based_poisson(dk.dim, dk.plane);
  mat.shape = dk.shape;
  mat.plane = dk.plane;
  mat.thickness = dk.thickness;
  mat.bb_equivalent_E = dk.E;
  m.formulation = *Formulation::named(dk.formulation, dk.dual_horizon &&
                                                         dk.solver != Deck::SolverType::Static);
  if (m.formulation.state_based()) {
    mat.nu = *dk.nu;
    mat.lps_constants = lps_constants(dk.dim, dk.plane, dk.E, mat.nu);
    mat.bb_equivalent_E = p_wave_modulus(dk.dim, dk.plane, dk.E, mat.nu) /
                          p_wave_modulus(dk.dim, dk.plane, 1.0, bond_based_poisson(dk.dim, dk.plane));
  }
  mat.c0 = micromodulus_c0(dk.dim, dk.plane, dk.shape, mat.bb_equivalent_E, dk.horizon, dk.thickness);
  if (m.formulation.keeps_bond_history())
    mat.onset_stretch = dk.law_stress / all_round_modulus(dk.dim, dk.plane, dk.E);
  if (dk.G0) {
    mat.G0 = *dk.G0;
    const double sb = brittle_critical_stretch(m.formulation, dk.dim, mat, mat.c0, dk.horizon);
    // Past the brittle critical stretch a history law could not dissipate G0 (it would yield or
    // soften after a brittle bond had already broken).
    if (m.formulation.keeps_bond_history() && !(mat.onset_stretch < sb))
      throw DeckError(dk.file, 0, 0, "material." + std::string(m.formulation.law->stress_key),
                      fmt::format("{} Pa is a bond stretch of {:.4g}, at or above {:.4g}, where "
                                  "a brittle bond breaks with this fracture_energy and horizon; "
                                  "give a smaller stress or a larger fracture_energy",
                                  dk.law_stress, mat.onset_stretch, sb));
    mat.s0 = breaking_stretch(m.formulation, dk.dim, mat, mat.c0, dk.horizon);
  } else if (dk.s0) {
    mat.s0 = *dk.s0;
  } else {
    mat.s0 = INFINITY;
  }
  mat.wave_speed = std::sqrt(p_wave_modulus(dk.dim, dk.plane, dk.E, mat.nu) / dk.rho);
  mat.lattice_calibration = dk.lattice_calibration;
  m.quadrature.rule = dk.quadrature;
  const double tol = 1e-9 * dk.grid.spacing;
  if (!dk.blocks.empty()) assign_blocks(dk, m, tol);
  const double calibration = micromodulus_factor(m, dk.horizon_factor);
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const MaterialLaw& law = node_material(m, i);
    ns.horizon[i] = dk.horizon;
    ns.density[i] = law.rho;
    ns.micromodulus[i] = law.c0 * calibration;
    ns.critical_stretch[i] = law.s0;
  }
  m.damage_enabled = dk.damage;
  m.pdro = dk.pdro;
  m.contact = dk.contact;
  m.impactors = dk.impactors;
  // Own counters and scratch: models built from one deck must not share them.
  m.pdro.counters = std::make_shared<PdroCounters>();
  m.pdro.visible_beta = std::make_shared<std::vector<float>>();
  mat.thermal_strain = dk.thermal_strain;

  QuadratureSpec qs;
  qs.rule = dk.quadrature;
  qs.lattice_rotation = dk.grid.rotation_deg * 3.14159265358979323846 / 180.0;
  const auto t0 = std::chrono::steady_clock::now();
  // An adaptive run appends refined rows: spare capacity now saves its first event a copy of
  // every bond.
  m.bonds = families ? families(ns, qs, m.partition)
                     : build_families(ns, qs, dk.adapt.enabled ? kRefinementBondHeadroom : 0.0);
  if (m.formulation.keeps_bond_history()) m.bonds.enable_state();
  m.family_build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  m.surface_correction = dk.surface_correction;
  m.interface_fit = dk.adapt.interface_fit;
  m.ghost.enabled = dk.adapt.ghost_correction;
  // Held rows: the per-node values of a correction come from each row's owner.
  HeldRowsShare held;
  held.owners = [&](std::vector<double>& v, int per_node) {
    share_owned_values(m.partition, v, per_node);
  };
  held.max = [](double v) { return mpi::max_real(v); };
  apply_surface_correction(ns, m.bonds, dk.shape, p_wave_modulus(dk.dim, dk.plane, dk.E, mat.nu),
                           m.surface_correction, m.formulation.state_based(),
                           block_uniaxial_moduli(m), m.partition.rows_held ? &held : nullptr);
  // A node on a crack is on neither side: it keeps its bonds to both faces and ties them
  // together, a crack that is not one (and which side a node within round-off of the line
  // falls on would be round-off). Refinement puts children at sub-cell centres (method B) or on
  // the half-spacing lattice, cell edges included (method A): those of every level the run can
  // reach count too.
  const bool refines = dk.adapt.enabled || !dk.adapt.initial.empty();
  const int child_levels = refines ? dk.adapt.max_level : 0;
  const ChildLattice lattice{dk.adapt.method == NodeGeneration::A, qs.lattice_rotation};
  // Method B's children never lie on a cell edge; method A's lattice has every multiple of
  // h / 2^max_level: a crack half that far from a node row avoids both.
  const double clear_offset = lattice.method_a && child_levels > 0
                                  ? dk.grid.spacing / static_cast<double>(2 << child_levels)
                                  : 0.5 * dk.grid.spacing;
  for (std::size_t c = 0; c < dk.cracks.size(); ++c) {
    int level = 0;
    Vec3 p{0, 0, 0};
    const std::size_t on = points_on_precrack(ns, dk.cracks[c], child_levels, lattice, &level, &p);
    if (mpi::max(static_cast<long>(on)) == 0) continue;
    const std::string what = level == 0 ? fmt::format("{} node{}", on, on == 1 ? "" : "s")
                                        : fmt::format("{} node{} of refinement level {}", on,
                                                      on == 1 ? "" : "s", level);
    const std::string where =
        on ? fmt::format(" (the first at ({:.6g}, {:.6g}, {:.6g}) m)", p[0], p[1], p[2]) : "";
    throw DeckError(dk.file, c < dk.crack_at.size() ? dk.crack_at[c] : DeckPlace{"cracks[" + std::to_string(c) + "]"},
                    fmt::format("the pre-crack passes through {}{}: a node on it keeps its bonds "
                                "to both faces and bridges the crack. Move the crack off the "
                                "nodes, e.g. {:.6g} m from a node row{}",
                                what, where, clear_offset,
                                lattice.method_a && child_levels > 0
                                    ? " (method a puts nodes on every multiple of the spacing / 2^max_level)"
                                    : " (onto a cell edge, which no level's nodes lie on)"));
  }
  std::vector<std::size_t> cut_by;
  m.precrack_bonds = apply_precracks(ns, m.bonds, dk.cracks, nullptr, &cut_by);
  // A crack that cuts no bond (inside a hole, beside the body, in other units) does nothing.
  for (std::size_t c = 0; c < cut_by.size(); ++c)
    if (mpi::max(static_cast<long>(cut_by[c])) == 0)
      throw DeckError(dk.file, c < dk.crack_at.size() ? dk.crack_at[c] : DeckPlace{"cracks[" + std::to_string(c) + "]"},
                      "the pre-crack cuts no bond: it lies where the body has no nodes (a hole, "
                      "outside the body) or between nodes without crossing a bond");
  update_damage_weights(ns, m.bonds);
  m.quadrature = qs;
  m.cracks = dk.cracks;
  m.lattice_rotation = qs.lattice_rotation;
  m.body = dk.grid.body;
  for (int d = dk.dim; d < 3; ++d) m.body.lo[d] = -INFINITY, m.body.hi[d] = INFINITY;
  m.holes = dk.grid.holes;
  m.body_clip = dk.grid.clip;

  for (std::size_t r = 0; r < dk.no_fail.size(); ++r) {
    const std::vector<std::uint32_t> sel = select(ns, dk.no_fail[r], tol);
    if (sel.empty())
      throw DeckError(dk.file,
                      r < dk.no_fail_at.size() ? dk.no_fail_at[r]
                                               : DeckPlace{"damage.no_fail[" + std::to_string(r) + "]"},
                      "the region selects no nodes");
    for (std::uint32_t i : sel) ns.flags[i] |= kNoFail;
  }
  mark_unbreakable_bonds(ns, m.bonds);
  index_pairs(m.bonds, ns, m.formulation.dual_horizon, m.formulation.state_based());

  for (std::size_t r = 0; r < dk.output.regions.size(); ++r)
    if (select(ns, dk.output.regions[r].region, tol).empty())
      throw DeckError(dk.file, 0, 0, "output.regions[" + std::to_string(r) + "].region",
                      "the region selects no nodes");
  for (const LoadSpec& ls : dk.loads) {
    BodyLoad bl;
    bl.name = ls.name;
    bl.nodes = select(ns, ls.region, tol);
    if (bl.nodes.empty())
      throw DeckError(dk.file, ls.region_at, "the region selects no nodes");
    // A traction t spread over a layer of depth h acts as the body-force density t / h
    // (thesis ch. 6 loads one row of nodes). Without an explicit layer, h = (volume of the
    // selected nodes) / (area of the region's largest face), so that the total force is t times
    // that area whatever the node volumes (half cells on node-on-edge grids included).
    double scale = 1.0;
    if (ls.kind == LoadSpec::Kind::Traction) {
      double h = ls.layer;
      if (!(h > 0)) {
        if (ls.region.kind != Shape::Kind::Box)
          throw DeckError(dk.file, 0, 0, ls.name + ".layer",
                          "a traction on a non-box region needs an explicit layer depth (m)");
        std::vector<double> ext;
        for (int d = 0; d < dk.dim; ++d)
          ext.push_back(std::max(0.0, std::min(ls.region.box.hi[d], dk.grid.body.hi[d]) -
                                          std::max(ls.region.box.lo[d], dk.grid.body.lo[d])));
        std::sort(ext.begin(), ext.end());
        double area = dk.dim == 1 ? dk.thickness : dk.dim == 2 ? ext[1] * dk.thickness : ext[1] * ext[2];
        if (dk.dim == 2 && ext[1] <= 0) area = dk.grid.spacing * dk.thickness;  // a single node
        if (dk.dim == 3 && ext[1] * ext[2] <= 0) area = dk.grid.spacing * dk.grid.spacing;
        double vol = 0;
        for (std::uint32_t i : bl.nodes) vol += ns.volume[i];
        h = vol / area;
      }
      scale = 1.0 / h;
    }
    for (int d = 0; d < 3; ++d) bl.density[d] = ls.value[d] * scale;
    bl.amplitude = ls.time;
    m.loads.push_back(std::move(bl));
  }
  for (const MotionSpec& ms : dk.motions) {
    PrescribedMotion pm;
    pm.name = ms.name;
    pm.kind = ms.kind == MotionSpec::Kind::Velocity ? PrescribedMotion::Kind::Velocity
                                                    : PrescribedMotion::Kind::Displacement;
    pm.nodes = select(ns, ms.region, tol);
    pm.region = ms.region;
    if (pm.nodes.empty())
      throw DeckError(dk.file, ms.region_at, "the region selects no nodes");
    for (int d = 0; d < 3; ++d) {
      if (!ms.component[d]) continue;
      pm.component[d] = Expression(*ms.component[d]);
      // A value that is not finite at the start would reach the fields unseen.
      for (std::uint32_t i : pm.nodes)
        if (const double v = (*pm.component[d])(ns.x[0][i], ns.x[1][i], ns.x[2][i], 0.0); !std::isfinite(v))
          throw DeckError(dk.file, ms.component_at[d],
                          fmt::format("'{}' is {} at t = 0 at the node ({:.6g}, {:.6g}, {:.6g}) of "
                                      "'{}'; a prescribed value must be finite",
                                      *ms.component[d], v, ns.x[0][i], ns.x[1][i], ns.x[2][i], ms.name));
    }
    for (std::uint32_t i : pm.nodes) ns.flags[i] |= kBoundary;
    m.motions.push_back(std::move(pm));
  }
  for (int d = 0; d < dk.dim; ++d) {
    const auto set = [&](const std::optional<std::string>& text, const DeckPlace& at,
                         std::vector<double>& field) {
      if (!text) return;
      Expression e(*text);
      for (std::size_t i = 0; i < ns.size(); ++i) {
        field[i] = e(ns.x[0][i], ns.x[1][i], ns.x[2][i], 0.0);
        if (!std::isfinite(field[i]))
          throw DeckError(dk.file, at,
                          fmt::format("'{}' is {} at the node ({:.6g}, {:.6g}, {:.6g}); an initial "
                                      "value must be finite on every node",
                                      *text, field[i], ns.x[0][i], ns.x[1][i], ns.x[2][i]));
      }
    };
    set(dk.initial_displacement[d], dk.initial_displacement_at[d], ns.u[d]);
    set(dk.initial_velocity[d], dk.initial_velocity_at[d], ns.v[d]);
  }
  ns.sync_all_current();
  {
    for (std::size_t k = 0; k < dk.adapt.initial.size(); ++k)
      if (select(ns, dk.adapt.initial[k].region, tol).empty())
        throw DeckError(dk.file,
                        k < dk.initial_refinement_at.size()
                            ? dk.initial_refinement_at[k]
                            : DeckPlace{"adapt.initial_refinement[" + std::to_string(k) + "].region"},
                        "the region selects no nodes: the zone would refine nothing");
    if (dk.adapt.region && select(ns, *dk.adapt.region, tol).empty())
      throw DeckError(dk.file, dk.adapt_region_at.value_or(DeckPlace{"adapt.region"}),
                      "the region selects no nodes: nothing could ever be refined");
  }
  if (AdaptSpec spec = dk.adapt; !(spec.initial = setup_zones(m, dk.adapt)).empty())
    apply_initial_refinement(m, spec);
  return m;
}

}  // namespace periadapt

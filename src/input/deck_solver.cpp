// Deck sections solver and adapt, and the rules that join them to the material and damage.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/expression.hpp"
#include "input/deck_sections.hpp"
#include "material/formulation.hpp"
#include "input/yaml_section.hpp"

namespace periadapt::deck_sections {

void parse_solver(Section& top, Deck& dk) {
  // --- solver
  {
    Section s = top.section("solver");
    const std::string type = s.choice("type", {"explicit", "static", "relaxation"}, "explicit");
    if (s.has("memory_limit_gb"))
      dk.memory_limit_gb = s.number("memory_limit_gb", std::nullopt, [](double v) {
        return (v > 0 && v <= 1e6) ? std::string() : std::string("must be in (0, 1e6] GB");
      });
    dk.solver = type == "static"       ? Deck::SolverType::Static
                : type == "relaxation" ? Deck::SolverType::Relaxation
                                       : Deck::SolverType::Explicit;
    if (dk.solver == Deck::SolverType::Relaxation) {
      for (const char* k : {"time_step", "end_time", "steps", "safety_factor", "multirate",
                            "multirate_ratio", "allow_unstable_time_step"})
        if (s.has(k))
          s.fail(k, "dynamic relaxation has no physical time step; use load_steps, tolerance "
                    "and max_iterations");
      dk.load_steps = static_cast<int>(s.integer("load_steps", 1, [](long v) {
        return (v >= 1 && v <= 1000000) ? std::string() : std::string("must be in 1 ... 1e6");
      }));
      dk.relax_tolerance = s.number("tolerance", 1e-6, [](double v) {
        return (v > 0 && v < 1) ? std::string() : std::string("a relative residual in (0, 1)");
      });
      dk.relax_max_iterations = s.integer("max_iterations", 200000, [](long v) {
        return v >= 1 ? std::string() : std::string("must be >= 1");
      });
    } else if (dk.solver == Deck::SolverType::Static) {
      if (!Formulation::named(dk.formulation)->bond_based())
        s.fail("type", "the linear static solve assembles the bond-based stiffness; for the LPS "
                       "model use type: relaxation");
      // Linearized equilibrium: no time stepping keys, no bond breaking.
      for (const char* k : {"time_step", "end_time", "steps", "safety_factor", "multirate",
                            "multirate_ratio", "allow_unstable_time_step"})
        if (s.has(k))
          s.fail(k, "a static solve has no time stepping; remove this key or use type: explicit");
      dk.solver_type_at = s.place("type");
      dk.damage = false;
    } else {
      if (s.has("time_step")) {
        dk.time_step = s.number("time_step", std::nullopt, positive());
        dk.time_step_at = s.place("time_step");
      }
      dk.safety = s.number("safety_factor", 0.8, [](double v) {
        return (v > 0 && v <= 1) ? std::string() : std::string("must be in (0, 1]");
      });
      dk.allow_unstable_time_step = s.boolean("allow_unstable_time_step", false);
      dk.multirate = s.boolean("multirate", false);
      if (s.has("multirate_ratio") && !dk.multirate)
        s.fail("multirate_ratio", "the largest step ratio of multi-rate stepping needs "
                                  "multirate: true");
      dk.multirate_ratio = static_cast<int>(s.integer("multirate_ratio", 2, [](long v) {
        return (v >= 2 && v <= 4) ? std::string() : std::string("an integer 2, 3 or 4");
      }));
      if (dk.multirate && !Formulation::named(dk.formulation)->row_local())
        s.fail("multirate", "multi-rate stepping needs row-local forces: formulation: pmb (the LPS "
                            "dilatation couples every node to its neighbours' rows)");
      if (s.has("end_time") == s.has("steps"))
        s.fail("", "give exactly one of end_time (s) or steps");
      if (s.has("end_time")) dk.end_time = s.number("end_time", std::nullopt, positive());
      if (s.has("steps"))
        dk.steps = s.integer("steps", std::nullopt, [](long v) {
          return v >= 1 ? std::string() : std::string("must be >= 1");
        });
    }
    dk.dual_horizon =
        s.choice("bond_pairing", {"source_horizon", "dual_horizon"}, "source_horizon") ==
        "dual_horizon";
    if (dk.multirate && dk.dual_horizon)
      s.fail("multirate", "multi-rate stepping needs bond_pairing: source_horizon (dual-horizon "
                          "forces act on both ends of a bond)");
    // How mpirun runs split the rows (parallel/row_partition.hpp).
    dk.partition = s.choice("partition", {"rcb", "hsfc"}, "rcb") == "rcb" ? PartitionMethod::Rcb
                                                                          : PartitionMethod::Hsfc;
    dk.rebalance_threshold = s.number("rebalance_threshold", dk.rebalance_threshold, [](double v) {
      return (v >= 0.01 && v <= 10) ? std::string()
                                    : std::string("must be in [0.01, 10] (largest rank's bonds over "
                                                  "the mean, less 1)");
    });
    dk.owned_integration = s.boolean("owned_integration", true);
    s.finish();
  }
  if (auto c = top.optional_section("contact")) {
    ContactSpec& cs = dk.contact;
    cs.enabled = c->boolean("enabled", true);
    cs.stiffness_factor = c->number("stiffness_factor", cs.stiffness_factor, [](double v) {
      return (v > 0 && v <= 1000) ? std::string() : std::string("must be in (0, 1000] (times c)");
    });
    cs.distance_factor = c->number("distance_factor", cs.distance_factor, [](double v) {
      return (v > 0 && v <= 1) ? std::string()
                               : std::string("must be in (0, 1] (of the reference distance)");
    });
    cs.spacing_factor = c->number("spacing_factor", cs.spacing_factor, [](double v) {
      return (v > 0 && v <= 3) ? std::string() : std::string("must be in (0, 3] (grid spacings)");
    });
    if (cs.enabled && dk.solver != Deck::SolverType::Explicit)
      c->fail("enabled", "contact forces are for explicit runs (solver.type: explicit); a static "
                         "or relaxation solve does not track them");
    if (cs.enabled && dk.multirate)
      c->fail("enabled", "contact couples nodes outside their bond rows; it needs every node on "
                         "every step (remove solver.multirate)");
    c->finish();
  }
  for (Section s : top.list("impactors")) {
    Impactor im;
    const std::size_t D = static_cast<std::size_t>(dk.dim);
    auto vec = [&](const std::string& key) {
      const std::vector<double> v = s.numbers(key, D, D);
      Vec3 out{0, 0, 0};
      for (std::size_t d = 0; d < D; ++d) out[d] = v[d];
      return out;
    };
    im.shape = s.choice("shape", {"sphere", "cylinder"}, "sphere") == "cylinder"
                   ? Impactor::Shape::Cylinder
                   : Impactor::Shape::Sphere;
    im.center = vec("center");
    im.radius = s.number("radius", std::nullopt, positive());
    im.mass = s.number("mass", std::nullopt, positive());
    if (s.has("velocity")) im.velocity = vec("velocity");
    im.stiffness_factor = s.number("stiffness_factor", im.stiffness_factor, [](double v) {
      return (v > 0 && v <= 1000) ? std::string() : std::string("must be in (0, 1000] (times c)");
    });
    if (im.shape == Impactor::Shape::Cylinder) {
      im.half_length = 0.5 * s.number("length", std::nullopt, positive());
      const Vec3 a = vec("axis");
      if (!(norm(a) > 0)) s.fail("axis", "the cylinder's axis must be a non-zero vector");
      im.axis = scale(a, 1.0 / norm(a));
    } else {
      for (const char* k : {"length", "axis"})
        if (s.has(k)) s.fail(k, "a sphere has no length or axis (shape: cylinder has)");
    }
    if (dk.dim == 1) s.fail("shape", "impactors strike 2D and 3D bodies");
    if (dk.solver != Deck::SolverType::Explicit)
      s.fail("", "impactors move in explicit runs (solver.type: explicit)");
    if (dk.multirate)
      s.fail("", "an impactor touches any node; it needs every node on every step (remove "
                 "solver.multirate)");
    s.finish();
    dk.impactors.push_back(im);
  }
  const Formulation f = *Formulation::named(dk.formulation, dk.dual_horizon);
  if (dk.pdro.enabled && !f.takes_overlay())
    top.fail("damage", f.dual_horizon
                           ? "the refinement overlay works with bond_pairing: source_horizon (pmb "
                             "or lps); the dual-horizon kernels do not re-check bonds"
                           : "the refinement overlay re-checks brittle bonds (pmb or lps); "
                             "formulation " + dk.formulation + " breaks bonds by its own history");
  if (dk.lattice_calibration && !f.bond_based())
    top.optional_section("discretization")
        ->fail("micromodulus_calibration",
               "lattice calibrates bond-based micromoduli; formulation " + dk.formulation +
                   " normalizes by its discrete weighted volume already (use analytic)");
  if (dk.thermal_strain != 0.0 &&
      (dk.solver != Deck::SolverType::Explicit || !f.takes_thermal_strain()))
    top.fail("material", "thermal_strain is supported by the explicit pmb solver with "
                         "bond_pairing: source_horizon only");
  if (dk.damage && !dk.G0 && !dk.s0)
    top.fail("material", "damage is enabled: give material.fracture_energy (G0) or "
                         "material.critical_stretch, or set damage.enabled: false");
}

void parse_adapt(Section& top, Deck& dk) {
  // --- adaptive grid refinement and scaling
  if (auto a = top.optional_section("adapt")) {
    AdaptSpec& ad = dk.adapt;
    ad.allow_unstable_step = dk.allow_unstable_time_step;
    int initial_top = 0;
    for (Section z : a->list("initial_refinement")) {
      InitialRefinement ir;
      ir.region = parse_region(z.section("region"), dk.dim);
      dk.initial_refinement_at.push_back(z.place("region"));
      ir.level = static_cast<int>(z.integer("level", std::nullopt, [](long v) {
        return (v >= 1 && v <= 6) ? std::string() : std::string("must be in 1 ... 6");
      }));
      initial_top = std::max(initial_top, ir.level);
      z.finish();
      ad.initial.push_back(ir);
    }
    ad.visibility = a->boolean("visibility", true);
    ad.max_level = static_cast<int>(a->integer("max_level", std::max(1, initial_top), [](long v) {
      return (v >= 1 && v <= 6) ? std::string() : std::string("must be in 1 ... 6");
    }));
    if (initial_top > ad.max_level)
      a->fail("max_level", "is below the level of an initial_refinement zone (" +
                               std::to_string(initial_top) + ")");
    ad.method = a->choice("method", {"B", "A"}, "B") == "A" ? NodeGeneration::A : NodeGeneration::B;
    const std::string sc = a->choice("scaling", {"delta", "m", "delta_m"}, "delta");
    ad.scaling = sc == "delta" ? HorizonScaling::Delta
                 : sc == "m"   ? HorizonScaling::M
                               : HorizonScaling::DeltaM;
    if (ad.scaling == HorizonScaling::DeltaM) {
      // One m per level the run can reach: a longer list names levels max_level never allows.
      const auto levels = static_cast<std::size_t>(ad.max_level + 1);
      ad.m_per_level = a->numbers("m_per_level", levels, levels);
      for (double v : ad.m_per_level)
        if (!(v >= 1.0)) a->fail("m_per_level", "every m must be >= 1");
      if (std::abs(ad.m_per_level[0] - dk.horizon_factor) > 1e-9 * dk.horizon_factor)
        a->fail("m_per_level", "the first entry is level 0 and must equal the grid's m = " +
                                   std::to_string(dk.horizon_factor));
    } else if (a->has("m_per_level")) {
      a->fail("m_per_level", "only used with scaling: delta_m");
    }
    ad.start_time = a->number("start_time", 0.0, non_negative());
    ad.check_every = static_cast<int>(a->integer("check_every", 1, [](long v) {
      return v >= 1 ? std::string() : std::string("must be >= 1");
    }));
    if (a->has("energy_trigger"))
      ad.energy_fraction = a->number("energy_trigger", std::nullopt, [](double v) {
        return (v > 0 && v <= 1) ? std::string()
                                 : std::string("a fraction of the maximum energy density in (0, 1]");
      });
    if (a->has("stretch_trigger"))
      ad.stretch_fraction = a->number("stretch_trigger", std::nullopt, [](double v) {
        return (v > 0 && v <= 1) ? std::string()
                                 : std::string("a fraction of the critical stretch of a node's "
                                               "children in (0, 1]");
      });
    // A deck that names no trigger and no initial zone gets the triggers that need no tuning:
    // bonds at half their children's critical stretch, and damage growth on a coarse node.
    const bool defaults = !ad.energy_fraction && !ad.stretch_fraction &&
                          !a->has("damage_trigger") && ad.initial.empty() &&
                          dk.solver == Deck::SolverType::Explicit;
    if (defaults) ad.stretch_fraction = kDefaultStretchTrigger;
    ad.damage_trigger = a->boolean("damage_trigger", defaults);
    ad.stretch_reach = a->number("stretch_reach", defaults ? kDefaultStretchReach : 0.0,
                                 [](double v) {
                                   return (v >= 0 && v <= 100)
                                              ? std::string()
                                              : std::string("horizons around cracked nodes in "
                                                            "[0, 100] (0: everywhere)");
                                 });
    if (ad.stretch_reach > 0 && !ad.stretch_fraction)
      a->fail("stretch_reach", "bounds the stretch trigger; give stretch_trigger too (or leave "
                               "the triggers out for the automatic profile)");
    if (ad.stretch_reach > 0 && !ad.damage_trigger)
      a->fail("stretch_reach", "beyond the reach only the damage trigger refines (a step that "
                               "breaks a coarse bond is redone refined); set damage_trigger: true "
                               "or stretch_reach: 0");
    ad.refine_crack_tips = a->boolean("refine_crack_tips", defaults);
    ad.refine_motions = a->boolean("refine_motions", defaults);
    // With the automatic triggers the zone follows the stretch field closely, and its interfaces
    // come near stressed free surfaces: without the correction a crack starts where an interface
    // meets a hole instead of at the hole's stress peak.
    ad.interface_horizon = a->boolean("interface_horizon", defaults);
    // The widened horizon is a quadrature repair; the thesis (F-14) also takes the critical
    // stretch of the widened horizon, which breaks interface bonds at about 0.8 (method B, m = 3)
    // of the strain the level's other nodes hold.
    ad.interface_level_stretch = a->choice("interface_stretch", {"level", "horizon"}, "level") == "level";
    if (a->has("interface_stretch") && !ad.interface_horizon)
      a->fail("interface_stretch", "only used with interface_horizon: true");
    ad.refine_loads = a->boolean("refine_loads", defaults && ad.method == NodeGeneration::B);
    ad.interface_fit = a->boolean("interface_fit", false);
    // A zone without its boundary cells keeps the coarse grid's staircase at holes and clipped
    // bodies, whose re-entrant corners break bonds the fine grid keeps.
    ad.fill_boundary_cells = a->boolean("fill_boundary_cells", defaults && ad.method == NodeGeneration::B);
    if (ad.fill_boundary_cells && ad.method == NodeGeneration::A)
      a->fail("fill_boundary_cells", "fills the empty cells next to method B's parents (method A "
                                     "places its lattice around each parent already); use method B");
    if (ad.interface_fit && !Formulation::named(dk.formulation)->bond_based())
      a->fail("interface_fit", "the fit zeroes the third bond moments that a bond-based force "
                               "sums; formulation " + dk.formulation + " is state-based");
    if (ad.interface_fit && dk.dual_horizon)
      a->fail("interface_fit", "the fit makes each row's own bond sum pass the patch test; the "
                               "dual-horizon pairing adds other rows' memberships (use "
                               "bond_pairing: source_horizon)");
    ad.ghost_correction = a->boolean("ghost_correction", false);
    if (ad.ghost_correction && dk.dual_horizon)
      a->fail("ghost_correction", "the correction acts on each row's own force; the dual-horizon "
                                  "pairing conserves energy and would lose it (use bond_pairing: "
                                  "source_horizon)");
    if (ad.ghost_correction && Formulation::named(dk.formulation)->keeps_bond_history())
      a->fail("ghost_correction", "the table is the elastic response of each row; formulation " +
                                      dk.formulation + " keeps a bond history (pmb or lps only)");
    if (ad.ghost_correction && dk.solver == Deck::SolverType::Static)
      a->fail("ghost_correction", "the static solver assembles the bond stiffness directly; the "
                                  "correction is for explicit and relaxation runs");
    if (ad.refine_loads && ad.method == NodeGeneration::A)
      a->fail("refine_loads", "method a shrinks the loaded parents' cells without handing the "
                              "lost load to the new nodes; use method b");
    ad.total_energy = a->choice("energy", {"strain", "total"}, "strain") == "total";
    ad.coarsen = a->boolean("coarsen", false);
    ad.conserve_energy = a->boolean("conserve_energy", false);
    ad.relax_sweeps = static_cast<int>(a->integer("relax_sweeps", 0, [](long v) {
      return (v >= 0 && v <= 100) ? std::string() : std::string("must be in 0 ... 100");
    }));
    if (ad.coarsen && ad.method == NodeGeneration::A)
      a->fail("coarsen", "coarsening restores parents from their children (method b); method a "
                         "keeps the parents and is not coarsened");
    if (ad.coarsen && Formulation::named(dk.formulation)->keeps_bond_history())
      a->fail("coarsen", "a restored parent's bonds would start without the plastic or softening "
                         "history its children's bonds carried (formulation " + dk.formulation +
                         "); leave coarsening off");
    if (ad.coarsen && !ad.energy_fraction)
      a->fail("coarsen", "coarsening needs the energy trigger (it coarsens where the energy "
                         "is below the trigger level)");
    ad.visibility_factor = a->number("visibility_factor", 1.0, [](double v) {
      return (v >= 1.0 && v <= 20.0) ? std::string() : std::string("must be in [1, 20] horizons");
    });
    ad.enabled = ad.energy_fraction || ad.stretch_fraction || ad.damage_trigger;
    if (!ad.enabled && ad.initial.empty())
      a->fail("", dk.solver == Deck::SolverType::Explicit
                      ? "give at least one trigger (stretch_trigger: fraction of the critical "
                        "stretch, energy_trigger: fraction of W_max, damage_trigger: true) or an "
                        "initial_refinement zone"
                      : "static and relaxation runs refine only initial_refinement zones (the "
                        "automatic profile and the triggers act between time steps of explicit "
                        "runs): give the zones, or use solver.type: explicit");
    for (const char* key : {"refine_crack_tips", "refine_motions"})
      if (a->has(key) && a->boolean(key, false) && !ad.enabled)
        a->fail(key, "refines before the run for a run's triggers (explicit runs); without a "
                     "trigger give the zone as initial_refinement");
    ad.relax_until_crack = a->boolean("relax_until_crack", false);
    if (ad.relax_until_crack && ad.relax_sweeps == 0)
      a->fail("relax_until_crack", "limits the relaxed events (relax_sweeps) to those before the "
                                   "first broken bond; give relax_sweeps too");
    if (ad.relax_until_crack && !ad.damage_trigger)
      a->fail("relax_until_crack", "the first broken bond is seen by the damage trigger; set "
                                   "damage_trigger: true (or leave the triggers out)");
    if (ad.relax_sweeps > 0 && !ad.enabled)
      a->fail("relax_sweeps", "relaxes the events of a run's triggers; initial_refinement zones "
                              "are made before any field exists (give a trigger, or leave it out)");
    if (ad.enabled && dk.solver != Deck::SolverType::Explicit)
      a->fail("", "refinement triggers work with the explicit solver only; static and relaxation "
                  "runs take initial_refinement zones");
    if (a->has("region")) {
      ad.region = parse_region(a->section("region"), dk.dim);
      dk.adapt_region_at = a->place("region");
    }
    a->finish();
  }
}

}  // namespace periadapt::deck_sections

// Deck sections loads, boundary_conditions, initial_conditions and damage.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/expression.hpp"
#include "input/deck_sections.hpp"
#include "io/csv_column.hpp"
#include "input/yaml_section.hpp"

namespace periadapt::deck_sections {

void parse_loading_and_damage(Section& top, Deck& dk) {
  // --- loads
  for (Section l : top.list("loads")) {
    LoadSpec ls;
    std::string t = l.choice("type", {"traction", "body_force"});
    ls.kind = t == "traction" ? LoadSpec::Kind::Traction : LoadSpec::Kind::BodyForce;
    ls.name = l.text("name", l.path());
    for (const LoadSpec& other : dk.loads)
      if (csv_column_stem("", other.name) == csv_column_stem("", ls.name))
        l.fail("name", other.name == ls.name
                           ? "another load is named '" + ls.name +
                                 "'; a name labels history.csv's columns and plots, so each load "
                                 "needs its own"
                           : "'" + ls.name + "' and another load's name '" + other.name +
                                 "' give the same history.csv columns (load_" +
                                 csv_column_stem("", ls.name) +
                                 "_...: characters other than letters and digits become '_'); "
                                 "rename one");
    ls.region = parse_region(l.section("region"), dk.dim);
    ls.region_at = l.place("region");
    ls.value = to_vec(l.numbers("value", static_cast<std::size_t>(dk.dim),
                                static_cast<std::size_t>(dk.dim)));
    if (ls.kind == LoadSpec::Kind::Traction) ls.layer = l.number("layer", 0.0, non_negative());
    ls.time = parse_time(l.optional_section("time"));
    l.finish();
    dk.loads.push_back(ls);
  }
  // --- boundary conditions
  for (Section b : top.list("boundary_conditions")) {
    MotionSpec ms;
    ms.name = b.text("name", b.path());
    for (const MotionSpec& other : dk.motions)
      if (csv_column_stem("", other.name) == csv_column_stem("", ms.name))
        b.fail("name", other.name == ms.name
                           ? "another boundary condition is named '" + ms.name +
                                 "'; a name labels history.csv's columns and plots, so each one "
                                 "needs its own"
                           : "'" + ms.name + "' and another boundary condition's name '" +
                                 other.name + "' give the same history.csv columns (bc_" +
                                 csv_column_stem("", ms.name) +
                                 "_...: characters other than letters and digits become '_'); "
                                 "rename one");
    ms.region = parse_region(b.section("region"), dk.dim);
    ms.region_at = b.place("region");
    if (b.has("velocity") == b.has("displacement"))
      b.fail("", "a boundary condition needs exactly one of: velocity, displacement");
    const bool vel = b.has("velocity");
    ms.kind = vel ? MotionSpec::Kind::Velocity : MotionSpec::Kind::Displacement;
    ms.component = parse_components(b, vel ? "velocity" : "displacement", dk.dim, &ms.component_at);
    b.finish();
    dk.motions.push_back(ms);
  }
  // --- initial conditions
  if (auto ic = top.optional_section("initial_conditions")) {
    if (ic->has("displacement"))
      dk.initial_displacement =
          parse_components(*ic, "displacement", dk.dim, &dk.initial_displacement_at);
    if (ic->has("velocity"))
      dk.initial_velocity = parse_components(*ic, "velocity", dk.dim, &dk.initial_velocity_at);
    ic->finish();
  }
  // --- damage
  if (auto dmg = top.optional_section("damage")) {
    dk.damage = dmg->boolean("enabled", true);
    for (Section r : dmg->list("no_fail")) {
      dk.no_fail.push_back(parse_region(r, dk.dim));
      dk.no_fail_at.push_back(r.place());
    }
    if (auto pd = dmg->optional_section("overlay")) {
      // Stewart & Jeon 2019 refinement overlay: bonds re-checked on a virtual sub-grid dx / n.
      dk.pdro.enabled = true;
      dk.pdro.n = pd->number("n", std::nullopt, [](double v) {
        return (v > 1.0 && v <= 20.0) ? std::string()
                                      : std::string("the sub-grid ratio dx/dx' must be in (1, 20]");
      });
      if (pd->has("region")) dk.pdro.region = parse_region(pd->section("region"), dk.dim);
      dk.pdro.interpolation = pd->choice("interpolation", {"pddo", "pim"}, "pddo") == "pim"
                                  ? PdroInterpolation::Pim
                                  : PdroInterpolation::Pddo;
      dk.pdro.weight = pd->choice("weight", {"uniform", "gaussian"}, "uniform") == "gaussian"
                           ? PddoWeight::Gaussian
                           : PddoWeight::Uniform;
      dk.pdro.sampling = pd->choice("sampling", {"three_pairs", "whole_bond"}, "three_pairs") == "whole_bond"
                             ? PdroSampling::WholeBond
                             : PdroSampling::ThreePairs;
      pd->finish();
      // (bond_pairing is read later: checked below with the solver section)
    }
    dmg->finish();
  }
}

}  // namespace periadapt::deck_sections

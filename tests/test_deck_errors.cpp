// Bad decks give one clear error naming the file, the key, the line and what is allowed.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "input/deck.hpp"
#include "input/deck_builder.hpp"
#include "input/deck_error.hpp"
#include "setup/build_model.hpp"

using namespace periadapt;

namespace {

const char* kGood =
    "model:\n"
    "  dimension: 2\n"
    "material:\n"
    "  youngs_modulus: 72.0e9\n"
    "  density: 2440\n"
    "  fracture_energy: 135\n"
    "discretization:\n"
    "  spacing: 0.001\n"
    "  horizon_factor: 3\n"
    "  body: {box: {min: [0, 0], max: [0.1, 0.04]}}\n"
    "cracks:\n"
    "  - segment: [[0, 0.02], [0.05, 0.02]]\n"
    "solver:\n"
    "  end_time: 1.0e-6\n";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

DeckError expect_error(const std::string& yaml) {
  try {
    parse_deck(yaml, "bad.yaml");
  } catch (const DeckError& e) {
    return e;
  }
  ADD_FAILURE() << "deck was accepted:\n" << yaml;
  return DeckError("", 0, 0, "", "");
}

DeckError expect_error_with(const std::string& yaml, const std::vector<std::string>& overrides) {
  try {
    parse_deck(yaml, "bad.yaml", overrides);
  } catch (const DeckError& e) {
    return e;
  }
  ADD_FAILURE() << "deck was accepted with the overrides";
  return DeckError("", 0, 0, "", "");
}

bool contains(const DeckError& e, const std::string& s) {
  return std::string(e.what()).find(s) != std::string::npos;
}

}  // namespace

TEST(DeckErrors, GoodDeckParses) { EXPECT_NO_THROW(parse_deck(kGood, "good.yaml")); }

TEST(DeckErrors, UnknownKeySuggestsTheRightOne) {
  DeckError e = expect_error(replace(kGood, "  density: 2440", "  density: 2440\n  poison_ratio: 0.3"));
  EXPECT_EQ(e.key(), "material.poison_ratio");
  EXPECT_EQ(e.line(), 6);
  EXPECT_TRUE(contains(e, "bad.yaml:6:")) << e.what();
  EXPECT_TRUE(contains(e, "did you mean 'poisson_ratio'")) << e.what();
}

TEST(DeckErrors, MisspelledRequiredKeyIsReportedAsUnknown) {
  DeckError e = expect_error(replace(kGood, "youngs_modulus", "young_modulus"));
  EXPECT_EQ(e.key(), "material.young_modulus");
  EXPECT_TRUE(contains(e, "did you mean 'youngs_modulus'")) << e.what();
}

TEST(DeckErrors, NegativeModulus) {
  DeckError e = expect_error(replace(kGood, "72.0e9", "-72.0e9"));
  EXPECT_EQ(e.key(), "material.youngs_modulus");
  EXPECT_EQ(e.line(), 4);
  EXPECT_TRUE(contains(e, "must be > 0")) << e.what();
}

TEST(DeckErrors, HorizonFactorBelowOne) {
  DeckError e = expect_error(replace(kGood, "horizon_factor: 3", "horizon_factor: 0.8"));
  EXPECT_EQ(e.key(), "discretization.horizon_factor");
  EXPECT_EQ(e.line(), 9);
  EXPECT_TRUE(contains(e, ">= 1")) << e.what();
}

TEST(DeckErrors, CrackOutsideTheBody) {
  DeckError e = expect_error(replace(kGood, "[[0, 0.02], [0.05, 0.02]]", "[[0.2, 0.02], [0.3, 0.02]]"));
  EXPECT_EQ(e.key(), "cracks[0].segment");
  EXPECT_EQ(e.line(), 12);
  EXPECT_TRUE(contains(e, "outside the body")) << e.what();
}

TEST(DeckErrors, MissingSection) {
  DeckError e = expect_error(replace(kGood, "solver:\n  end_time: 1.0e-6\n", ""));
  EXPECT_EQ(e.key(), "solver");
  EXPECT_TRUE(contains(e, "missing required section")) << e.what();
}

TEST(DeckErrors, MalformedYaml) {
  DeckError e = expect_error(replace(kGood, "  body: {box: {min: [0, 0], max: [0.1, 0.04]}}",
                                     "  body: {box: {min: [0, 0], max: [0.1, 0.04]}"));
  EXPECT_GT(e.line(), 0);
  EXPECT_TRUE(contains(e, "malformed YAML")) << e.what();
}

TEST(DeckErrors, WrongTypeAndBadChoice) {
  DeckError e1 = expect_error(replace(kGood, "spacing: 0.001", "spacing: fine"));
  EXPECT_EQ(e1.key(), "discretization.spacing");
  EXPECT_TRUE(contains(e1, "expected a number")) << e1.what();
  DeckError e2 = expect_error(replace(kGood, "  dimension: 2\n", "  dimension: 2\n  plane: stres\n"));
  EXPECT_TRUE(contains(e2, "allowed: stress, strain")) << e2.what();
}

TEST(DeckErrors, BadExpression) {
  DeckError e = expect_error(std::string(kGood) + "initial_conditions: {velocity: ['exp(x', '0']}\n");
  EXPECT_EQ(e.key(), "initial_conditions.velocity");
  EXPECT_TRUE(contains(e, "cannot parse expression")) << e.what();
  // An assignment where a comparison was meant; the comparisons themselves stay allowed.
  for (const char* v : {"x = 0.01 ? 1 : 0", "t += 1", "y*=2"}) {
    DeckError a = expect_error(std::string(kGood) + "initial_conditions: {velocity: ['" + v + "', '0']}\n");
    EXPECT_EQ(a.key(), "initial_conditions.velocity");
    EXPECT_TRUE(contains(a, "'=' assigns")) << a.what();
  }
  EXPECT_NO_THROW(parse_deck(std::string(kGood) +
                                 "initial_conditions: {velocity: ['x == 0 || x <= 1 && x >= 0 && x != 2', '0']}\n", "good.yaml"));
}

TEST(DeckErrors, PoissonRatioContradictingTheBondBasedModel) {
  DeckError e = expect_error(replace(kGood, "  density: 2440", "  density: 2440\n  poisson_ratio: 0.22"));
  EXPECT_EQ(e.key(), "material.poisson_ratio");
  EXPECT_TRUE(contains(e, "1/3")) << e.what();
}

TEST(DeckErrors, StretchTriggerIsAFractionOfTheCriticalStretch) {
  const DeckError e = expect_error(std::string(kGood) + "adapt: {max_level: 1, stretch_trigger: 1.5}\n");
  EXPECT_TRUE(contains(e, "bad.yaml:15:")) << e.what();
  EXPECT_TRUE(contains(e, "adapt.stretch_trigger")) << e.what();
  EXPECT_TRUE(contains(e, "(0, 1]")) << e.what();
}

TEST(DeckErrors, AdaptWithoutTriggersTakesTheDocumentedDefaults) {
  // adapt: {max_level: N} alone: stretch trigger at 0.5, damage trigger, interface horizons,
  // filled boundary cells (method B). Naming any trigger switches to the thesis' explicit form.
  const Deck d = parse_deck(std::string(kGood) + "adapt: {max_level: 1}\n", "good.yaml");
  ASSERT_TRUE(d.adapt.enabled);
  ASSERT_TRUE(d.adapt.stretch_fraction.has_value());
  EXPECT_EQ(*d.adapt.stretch_fraction, kDefaultStretchTrigger);
  EXPECT_TRUE(d.adapt.damage_trigger);
  EXPECT_TRUE(d.adapt.interface_horizon);
  EXPECT_TRUE(d.adapt.interface_level_stretch);
  EXPECT_TRUE(d.adapt.fill_boundary_cells);
  EXPECT_FALSE(d.adapt.energy_fraction.has_value());
  // Method A places its lattice around each parent: no boundary cells to fill.
  EXPECT_FALSE(parse_deck(std::string(kGood) + "adapt: {max_level: 1, method: A}\n", "good.yaml")
                   .adapt.fill_boundary_cells);
  const Deck e = parse_deck(std::string(kGood) + "adapt: {max_level: 1, energy_trigger: 0.5}\n",
                            "good.yaml");
  EXPECT_FALSE(e.adapt.stretch_fraction.has_value());
  EXPECT_FALSE(e.adapt.damage_trigger);
  EXPECT_FALSE(e.adapt.interface_horizon);
  EXPECT_FALSE(e.adapt.fill_boundary_cells);
}

TEST(DeckErrors, FractureEnergyAndCriticalStretchAreExclusive) {
  // Both would define s0; the deck must not silently take one of them.
  const DeckError e = expect_error(replace(kGood, "  fracture_energy: 135\n",
                                           "  fracture_energy: 135\n  critical_stretch: 1.0e-3\n"));
  EXPECT_TRUE(contains(e, "bad.yaml:7:")) << e.what();
  EXPECT_TRUE(contains(e, "material.critical_stretch")) << e.what();
  EXPECT_TRUE(contains(e, "not both")) << e.what();
}

TEST(DeckErrors, HorizonAndHorizonFactorAreExclusive) {
  const DeckError e = expect_error(replace(kGood, "  horizon_factor: 3\n",
                                           "  horizon_factor: 3\n  horizon: 0.003\n"));
  EXPECT_TRUE(contains(e, "discretization.horizon")) << e.what();
  EXPECT_TRUE(contains(e, "not both")) << e.what();
}

TEST(DeckErrors, CommandLineOverridesAreCheckedLikeTheDecksOwnKeys) {
  // --set key.path=value: the same deck as editing the file, and the same checks.
  const Deck edited = parse_deck(replace(kGood, "spacing: 0.001", "spacing: 0.002"), "a.yaml");
  const Deck set = parse_deck(kGood, "a.yaml", {"discretization.spacing=0.002", "adapt.max_level=2"});
  EXPECT_EQ(set.grid.spacing, edited.grid.spacing);
  EXPECT_EQ(set.horizon, edited.horizon);
  EXPECT_TRUE(set.adapt.enabled);
  EXPECT_EQ(set.adapt.max_level, 2);
  const Deck listed = parse_deck(kGood, "a.yaml", {"cracks.0.segment=[[0, 0.01], [0.05, 0.01]]"});
  ASSERT_EQ(listed.cracks.size(), 1u);
  EXPECT_TRUE(contains(expect_error_with(kGood, {"material.youngs_modulus=-1"}),
                       "key 'material.youngs_modulus': must be > 0"));
  EXPECT_TRUE(contains(expect_error_with(kGood, {"material.colour=red"}), "unknown key"));
  EXPECT_TRUE(contains(expect_error_with(kGood, {"cracks.3.segment=[]"}), "not an index"));
  EXPECT_TRUE(contains(expect_error_with(kGood, {"spacing"}), "expected key.path=value"));
  // An empty mapping where a list belongs is refused as in a deck file, not read as no cracks.
  EXPECT_TRUE(contains(expect_error_with(kGood, {"cracks={}"}), "expected a list, got a mapping"));
  EXPECT_EQ(parse_deck(kGood, "a.yaml", {"cracks=[]"}).cracks.size(), 0u);
}

// Every check of the loader, one row each: a valid deck broken by --set overrides must be refused
// with the row's key named and its reason given (and the unbroken deck must load).
TEST(DeckErrors, EveryLoaderCheckRefusesItsCaseNamingTheKey) {
  const std::string base =
      "model: {dimension: 2, plane: stress, thickness: 0.01}\n"
      "material: {youngs_modulus: 72.0e9, density: 2440, fracture_energy: 135}\n"
      "discretization: {spacing: 0.001, horizon_factor: 3, body: {box: {min: [0, 0], max: [0.1, 0.04]}}}\n"
      "cracks:\n  - segment: [[0, 0.02], [0.05, 0.02]]\n"
      "loads:\n  - {name: top, type: traction, region: {box: {min: [0, 0.039], max: [0.1, 0.04]}},"
      " value: [0, 1.0e6]}\n"
      "boundary_conditions:\n  - {name: left, region: {box: {min: [0, 0], max: [0.001, 0.04]}},"
      " velocity: [0, 0]}\n"
      "damage: {no_fail: [{box: {min: [0, 0.038], max: [0.1, 0.04]}}]}\n"
      "solver: {end_time: 1.0e-6}\n"
      "output: {directory: out, crack_tip: {threshold: 0.35}}\n";
  ASSERT_NO_THROW(parse_deck(base, "base.yaml"));
  struct Row {
    std::vector<std::string> set;
    const char* key;      // named in the message
    const char* because;  // part of the reason
  };
  const std::vector<Row> rows = {
      {{"model.dimension=4"}, "model.dimension", "1, 2 or 3"},
      {{"model.plane=axisymmetric"}, "model.plane", "allowed"},
      {{"model.thickness=-1"}, "model.thickness", ""},
      {{"model.formulation=state"}, "model.formulation", "allowed"},
      {{"material.youngs_modulus=0"}, "material.youngs_modulus", ""},
      {{"material.density=-2"}, "material.density", ""},
      {{"material.youngs_modulus=abc"}, "material.youngs_modulus", "expected a number"},
      {{"material.youngs_modulus=.nan"}, "material.youngs_modulus", "finite"},
      {{"material.poisson_ratio=0.2"}, "material.poisson_ratio", "fixes Poisson"},
      {{"material.critical_stretch=1e-3"}, "material.critical_stretch", "not both"},
      {{"material.fracture_energy=null"}, "material", "fracture_energy"},
      {{"model.formulation=lps", "material.poisson_ratio=0.5"}, "material.poisson_ratio", ""},
      {{"model.formulation=elastic_perfectly_plastic"}, "material.yield_stress", "missing"},
      {{"model.formulation=bilinear_softening", "material.peak_stress=-1"}, "material.peak_stress", ""},
      {{"model.formulation=bilinear_softening", "material.peak_stress=1e6",
        "material.fracture_energy=null", "material.critical_stretch=1e-3"},
       "material.fracture_energy", "needs the fracture energy"},
      {{"model.formulation=elastic_perfectly_plastic", "material.yield_stress=1e6",
        "material.fracture_energy=null", "material.critical_stretch=1e-3"},
       "material.critical_stretch", "derives its breaking stretch"},
      {{"model.formulation=bilinear_softening", "material.peak_stress=1e6", "damage.overlay.n=2"},
       "damage", "its own history"},
      {{"model.formulation=elastic_perfectly_plastic", "material.yield_stress=1e6",
        "adapt={max_level: 1, energy_trigger: 0.5, coarsen: true}"}, "adapt.coarsen", "history"},
      {{"discretization.spacing=0"}, "discretization.spacing", ""},
      {{"discretization.horizon=0.003"}, "discretization.horizon", "not both"},
      {{"discretization.horizon_factor=0.5"}, "discretization.horizon_factor", ""},
      {{"discretization.horizon_factor=null", "discretization.horizon=0.0005"},
       "discretization.horizon", "at least one grid spacing"},
      {{"discretization.quadrature=gauss"}, "discretization.quadrature", "allowed"},
      {{"discretization.body.box.max=[0.1]"}, "discretization.body.box.max", "expected 2 numbers"},
      {{"discretization.body.box.max=[-0.1, 0.04]"}, "discretization.body.box.max", ">= the min"},
      {{"discretization.body.box.max=[0.0005, 0.04]"}, "discretization.body", "one grid spacing"},
      {{"discretization.body={sphere: {center: [0, 0, 0], radius: 1}}"}, "discretization.body.sphere", "3D"},
      {{"discretization.body={box: {min: [0, 0], max: [1, 1]}, disk: {center: [0, 0], radius: 1}}"},
       "discretization.body", "exactly one"},
      {{"discretization.body={polygon: [[0, 0], [0.1, 0.04], [0.1, 0], [0, 0.03]]}"},
       "discretization.body.polygon", "simple"},
      {{"discretization.body={polygon: [[0, 0], [0.1, 0]]}"}, "discretization.body.polygon", "3 ... 1000"},
      {{"discretization.body={polygon: [[0, 0], [0.1, 0], [0.2, 0]]}"}, "discretization.body.polygon", "no area"},
      {{"discretization.body={polygon: [[0, 0], [0.1, x], [0, 0.1]]}"}, "discretization.body.polygon", "numbers"},
      {{"cracks.0.segment=[[0, 0.02], [0, 0.02]]"}, "cracks[0].segment", "must differ"},
      {{"cracks.0.segment=[[1, 1], [2, 2]]"}, "cracks[0].segment", "outside the body"},
      {{"loads.0.type=pressure"}, "loads[0].type", "allowed"},
      {{"loads.0.value=[0, 1, 2]"}, "loads[0].value", "expected 2 numbers"},
      {{"boundary_conditions.0.displacement=[0, 0]"}, "boundary_conditions[0]", "exactly one"},
      {{"solver.type=implicit"}, "solver.type", "allowed"},
      {{"solver.steps=10"}, "solver", "exactly one of end_time"},
      {{"solver.end_time=-1"}, "solver.end_time", ""},
      {{"solver.safety_factor=1.5"}, "solver.safety_factor", "(0, 1]"},
      {{"solver.multirate_ratio=3"}, "solver.multirate_ratio", "multirate: true"},
      {{"solver.multirate=true", "solver.multirate_ratio=5"}, "solver.multirate_ratio", "2, 3 or 4"},
      {{"solver.multirate=true", "model.formulation=lps", "material.poisson_ratio=0.25"},
       "solver.multirate", "row-local"},
      {{"solver.multirate=true", "solver.bond_pairing=dual_horizon"}, "solver.multirate", "source_horizon"},
      {{"solver.bond_pairing=both"}, "solver.bond_pairing", "allowed"},
      {{"solver.type=relaxation"}, "solver.end_time", "no physical time step"},
      {{"solver.type=static"}, "solver.end_time", "no time stepping"},
      {{"solver.type=static", "solver.end_time=null", "model.formulation=lps",
        "material.poisson_ratio=0.25"}, "solver.type", "relaxation"},
      {{"solver.memory_limit_gb=0"}, "solver.memory_limit_gb", "(0, 1e6]"},
      {{"damage.overlay={n: 2}", "solver.bond_pairing=dual_horizon"}, "damage", "source_horizon"},
      {{"material.thermal_strain=1e-3", "solver.bond_pairing=dual_horizon"}, "material", "thermal_strain"},
      {{"adapt={max_level: 7}"}, "adapt.max_level", ""},
      {{"adapt={max_level: 1, initial_refinement: [{region: {all: true}, level: 2}]}"},
       "adapt.max_level", "initial_refinement"},
      {{"adapt={m_per_level: [3, 3]}"}, "adapt.m_per_level", "delta_m"},
      {{"adapt={energy_trigger: 0.5, interface_stretch: level}"}, "adapt.interface_stretch", "interface_horizon"},
      {{"adapt={max_level: 1, interface_stretch: both}"}, "adapt.interface_stretch", "allowed"},
      {{"adapt={energy_trigger: 0.5, method: A, fill_boundary_cells: true}"}, "adapt.fill_boundary_cells", "method B"},
      {{"adapt={initial_refinement: [{region: {all: true}, level: 1}], refine_crack_tips: true}"},
       "adapt.refine_crack_tips", "trigger"},
      {{"adapt={scaling: delta_m, m_per_level: [4, 3]}"}, "adapt.m_per_level", "level 0"},
      {{"adapt={scaling: delta_m, max_level: 1, m_per_level: [3, 4, 5]}"}, "adapt.m_per_level", ""},
      {{"adapt={method: A, refine_loads: true, energy_trigger: 0.5}"}, "adapt.refine_loads", "method a"},
      {{"adapt={method: A, coarsen: true, energy_trigger: 0.5}"}, "adapt.coarsen", "method"},
      {{"adapt={coarsen: true, damage_trigger: true}"}, "adapt.coarsen", "energy trigger"},
      {{"adapt={energy_trigger: 0}"}, "adapt.energy_trigger", ""},
      {{"adapt={stretch_trigger: 1.5}"}, "adapt.stretch_trigger", ""},
      {{"adapt={max_level: 1, stretch_reach: -1}"}, "adapt.stretch_reach", "[0, 100]"},
      {{"adapt={stretch_trigger: 0.5, stretch_reach: 2}"}, "adapt.stretch_reach", "damage_trigger"},
      {{"adapt={energy_trigger: 0.5, damage_trigger: true, stretch_reach: 2}"}, "adapt.stretch_reach",
       "stretch_trigger"},
      {{"adapt={max_level: 1, relax_until_crack: true}"}, "adapt.relax_until_crack", "relax_sweeps"},
      {{"adapt={energy_trigger: 0.5, relax_sweeps: 5, relax_until_crack: true}"},
       "adapt.relax_until_crack", "damage_trigger"},
      {{"adapt={max_level: 1, relax_sweeps: 101}"}, "adapt.relax_sweeps", "0 ... 100"},
      {{"adapt={max_level: 1, relax_sweeps: -1}"}, "adapt.relax_sweeps", "0 ... 100"},
      {{"adapt={relax_sweeps: 5, initial_refinement: [{region: {all: true}, level: 1}]}"},
       "adapt.relax_sweeps", "trigger"},
      {{"adapt={energy_trigger: 0.5}", "solver.type=relaxation", "solver.end_time=null"}, "adapt", "explicit"},
      {{"output.vtu_snapshots=-1"}, "output.vtu_snapshots", "0 ... 100000"},
      {{"output.history_every=0"}, "output.history_every", ">= 1"},
      {{"output.checkpoint_every=-5"}, "output.checkpoint_every", ">= 0"},
      {{"output.png_width=50"}, "output.png_width", "[100, 8000]"},
      {{"output.crack_tip.direction=[0, 0]"}, "output.crack_tip.direction", "non-zero"},
      {{"output.crack_tip.threshold=2"}, "output.crack_tip.threshold", ""},
      {{"output.colour=blue"}, "output.colour", "unknown key"},
      {{"output.directory=''"}, "output.directory", "must name a folder"},
      {{"cracks.0.segment=[[.nan, 0.02], [0.05, 0.02]]"}, "cracks[0].segment", "finite"},
      {{"cracks.0.segment=[[0, 0.02], [.inf, 0.02]]"}, "cracks[0].segment", "finite"},
      {{"loads=[{name: top, type: traction, region: {box: {min: [0, 0.039], max: [0.1, 0.04]}}, "
        "value: [0, 1.0e6]}, {name: top, type: traction, region: {box: {min: [0, 0], max: [0.1, "
        "0.001]}}, value: [0, -1.0e6]}]"}, "loads[1].name", "another load is named 'top'"},
      {{"boundary_conditions=[{name: left, region: {box: {min: [0, 0], max: [0.001, 0.04]}}, "
        "velocity: [0, 0]}, {name: left, region: {box: {min: [0.099, 0], max: [0.1, 0.04]}}, "
        "velocity: [0, 0]}]"}, "boundary_conditions[1].name", "another boundary condition"},
      {{"loads=[{name: top load, type: traction, region: {box: {min: [0, 0.039], max: [0.1, 0.04]}}, "
        "value: [0, 1.0e6]}, {name: top_load, type: traction, region: {box: {min: [0, 0], max: [0.1, "
        "0.001]}}, value: [0, -1.0e6]}]"}, "loads[1].name", "same history.csv columns (load_top_load"},
      {{"boundary_conditions=[{name: left-edge, region: {box: {min: [0, 0], max: [0.001, 0.04]}}, "
        "velocity: [0, 0]}, {name: left.edge, region: {box: {min: [0.099, 0], max: [0.1, 0.04]}}, "
        "velocity: [0, 0]}]"}, "boundary_conditions[1].name", "same history.csv columns (bc_left_edge"},
      {{"output.regions=[{name: a/b, region: {all: true}}, {name: a_b, region: {all: true}}]"},
       "output.regions[1].name", "same history.csv columns (region_a_b"},
      {{"output.load_displacement={name: nobody}"}, "output.load_displacement.name", "top left"},
      {{"output.load_displacement={name: left, component: z}"}, "output.load_displacement.component", "allowed"},
  };
  for (const Row& r : rows) {
    std::string label;
    for (const auto& s : r.set) label += s + " ";
    SCOPED_TRACE(label);
    try {
      parse_deck(base, "bad.yaml", r.set);
      ADD_FAILURE() << "accepted";
    } catch (const DeckError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(std::string("'") + r.key), std::string::npos) << msg;
      EXPECT_NE(msg.find(r.because), std::string::npos) << msg;
      EXPECT_NE(msg.find("bad.yaml"), std::string::npos) << msg;
    }
  }
}

// yaml-cpp reads the first of two equal keys and a deck's first document only: what the user
// wrote second would be ignored.
TEST(DeckErrors, ARepeatedKeyOrASecondDocumentIsRefusedWithItsLine) {
  DeckError e = expect_error(replace(kGood, "  density: 2440\n", "  density: 2440\n  density: 1000\n"));
  EXPECT_EQ(e.key(), "material.density");
  EXPECT_EQ(e.line(), 6);
  EXPECT_TRUE(contains(e, "first on line 5")) << e.what();
  e = expect_error(std::string(kGood) + "solver:\n  end_time: 2.0e-6\n");
  EXPECT_EQ(e.key(), "solver");
  EXPECT_TRUE(contains(e, "twice")) << e.what();
  e = expect_error(replace(kGood, "  - segment: [[0, 0.02], [0.05, 0.02]]\n",
                           "  - {segment: [[0, 0.02], [0.05, 0.02]], segment: [[0, 0.01], [0.05, 0.01]]}\n"));
  EXPECT_EQ(e.key(), "cracks[0].segment");
  e = expect_error(std::string(kGood) + "---\noutput: {vtu_snapshots: 10}\n");
  EXPECT_EQ(e.line(), 15);
  EXPECT_TRUE(contains(e, "second YAML document")) << e.what();
  // A document marker before the deck, or a trailing one, leaves one document.
  EXPECT_NO_THROW(parse_deck(std::string("---\n") + kGood + "---\n", "good.yaml"));
  e = expect_error(std::string(kGood) + "...\n# the end\noutput: {vtu_snapshots: 10}\n");
  EXPECT_EQ(e.line(), 15);
}

// What only the grid can tell: a region that selects no node, a prescribed value that is not
// finite on its nodes at the start, a pre-crack inside a hole. Each names its key and the line it was written on.
TEST(DeckErrors, TheGridRefusesEmptyRegionsAndNonFiniteMotionsNamingTheLine) {
  const std::string base =
      "model: {dimension: 2, plane: stress}\n"                                              // 1
      "material: {youngs_modulus: 72.0e9, density: 2440, fracture_energy: 135}\n"           // 2
      "discretization: {spacing: 0.001, body: {box: {min: [0, 0], max: [0.02, 0.01]}}, "
      "holes: [{disk: {center: [0.015, 0.005], radius: 0.002}}]}\n"                         // 3
      "boundary_conditions:\n"                                                              // 4
      "  - name: pull\n"                                                                    // 5
      "    region: {box: {min: [0.019, 0], max: [0.02, 0.01]}}\n"                            // 6
      "    velocity: [\"1e-3 * t / (t + 1e-6)\", 0]\n"                                      // 7
      "damage:\n"                                                                           // 8
      "  no_fail:\n"                                                                        // 9
      "    - box: {min: [0, 0], max: [0.002, 0.01]}\n"                                       // 10
      "adapt:\n"                                                                            // 11
      "  max_level: 1\n"                                                                    // 12
      "  energy_trigger: 0.5\n"                                                             // 13
      "  region: {box: {min: [0.005, 0], max: [0.015, 0.01]}}\n"                            // 14
      "  initial_refinement:\n"                                                             // 15
      "    - {region: {box: {min: [0.009, 0.004], max: [0.011, 0.006]}}, level: 1}\n"        // 16
      "solver: {steps: 2}\n";
  ASSERT_NO_THROW(build_model(parse_deck(base, "grid.yaml")));
  struct Row {
    std::string from, to;
    const char* key;
    int line;
    const char* because;
  };
  const std::vector<Row> rows = {
      {"[0.019, 0], max: [0.02, 0.01]", "[0.05, 0], max: [0.06, 0.01]", "boundary_conditions[0].region",
       6, "selects no nodes"},
      {"1e-3 * t / (t + 1e-6)", "1e-3 / t", "boundary_conditions[0].velocity[0]", 7, "at t = 0"},
      {"1e-3 * t / (t + 1e-6)", "sqrt(-1 - x)", "boundary_conditions[0].velocity[0]", 7, "finite"},
      {"[0, 0], max: [0.002, 0.01]", "[0.1, 0], max: [0.2, 0.01]", "damage.no_fail[0]", 10,
       "selects no nodes"},
      {"[0.005, 0], max: [0.015, 0.01]", "[0.5, 0], max: [0.6, 0.01]", "adapt.region", 14,
       "nothing could ever be refined"},
      {"[0.009, 0.004], max: [0.011, 0.006]", "[0.3, 0.3], max: [0.4, 0.4]",
       "adapt.initial_refinement[0].region", 16, "refine nothing"},
      {"solver: {steps: 2}", "cracks: [{segment: [[0.0145, 0.005], [0.0155, 0.005]]}]\nsolver: {steps: 2}",
       "cracks[0]", 17, "cuts no bond"},
      {"center: [0.015, 0.005], radius: 0.002", "center: [0.5, 0.5], radius: 0.002",
       "discretization.holes[0]", 3, "removes no node"},
      {"center: [0.015, 0.005], radius: 0.002", "center: [0.015, 0.005], radius: 0.0002",
       "discretization.holes[0]", 3, "between the grid points"},
      {"solver: {steps: 2}", "initial_conditions: {velocity: [\"sqrt(x - 0.01)\", 0]}\nsolver: {steps: 2}",
       "initial_conditions.velocity[0]", 17, "must be finite on every node"},
      {"max: [0.02, 0.01]}}, holes", "max: [1e308, 0.01]}}, holes", "discretization.spacing", 0,
       "discretization.body on line 3: its bounding box is 1e+308 x 0.01 m"},
  };
  for (const Row& r : rows) {
    SCOPED_TRACE(r.to);
    try {
      build_model(parse_deck(replace(base, r.from, r.to), "grid.yaml"));
      ADD_FAILURE() << "accepted";
    } catch (const DeckError& e) {
      EXPECT_EQ(e.key(), r.key) << e.what();
      EXPECT_EQ(e.line(), r.line) << e.what();
      EXPECT_TRUE(contains(e, r.because)) << e.what();
      EXPECT_TRUE(contains(e, "grid.yaml:")) << e.what();
    }
  }
}

TEST(DeckBuilder, BuildsWhatTheSameYamlReadsAndNamesABadKey) {
  const Deck text = parse_deck(
      "model: {dimension: 2, plane: strain}\n"
      "material: {youngs_modulus: 72.0e9, density: 2440, fracture_energy: 135}\n"
      "discretization: {spacing: 0.001, horizon_factor: 3.015, body: {box: {min: [0, 0], max: "
      "[0.1, 0.04]}}}\n"
      "loads:\n  - {name: top, type: traction, region: {box: {min: [0, 0.039], max: [0.1, 0.04]}},"
      " value: [0, 1.2e7]}\n"
      "initial_conditions: {velocity: [\"400 * x\", 0]}\n"
      "solver: {end_time: 1.0e-6}\n",
      "text.yaml");
  DeckBuilder b;
  b.set("model.dimension", 2)
      .set("model.plane", "strain")
      .set("material.youngs_modulus", 72.0e9)
      .set("material.density", 2440.0)
      .set("material.fracture_energy", 135.0)
      .set("discretization.spacing", 0.001)
      .set("discretization.horizon_factor", 3.015)
      .set("discretization.body.box.min", {0.0, 0.0})
      .set("discretization.body.box.max", {0.1, 0.04})
      .append("loads", DeckBuilder()
                           .set("name", "top")
                           .set("type", "traction")
                           .set("region.box.min", {0.0, 0.039})
                           .set("region.box.max", {0.1, 0.04})
                           .set("value", {0.0, 1.2e7}))
      .set("initial_conditions.velocity", std::vector<std::string>{"400 * x", "0"})
      .set("solver.end_time", 1.0e-6);
  const Deck built = b.build();
  EXPECT_EQ(built.dim, text.dim);
  EXPECT_EQ(built.plane, text.plane);
  EXPECT_EQ(built.E, text.E);
  EXPECT_EQ(built.G0, text.G0);
  EXPECT_EQ(built.horizon, text.horizon);  // 3.015 mm both ways: the doubles round-trip
  EXPECT_EQ(built.grid.body.hi, text.grid.body.hi);
  ASSERT_EQ(built.loads.size(), 1u);
  EXPECT_EQ(built.loads[0].value, text.loads[0].value);
  EXPECT_EQ(built.loads[0].region.box.lo, text.loads[0].region.box.lo);
  EXPECT_EQ(built.initial_velocity[0], text.initial_velocity[0]);
  EXPECT_EQ(built.end_time, text.end_time);
  try {
    b.set("material.youngs_modulus", -1.0).build();
    FAIL() << "a negative modulus was accepted";
  } catch (const DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("material.youngs_modulus"), std::string::npos) << e.what();
  }
}

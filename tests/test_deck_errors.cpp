// Bad decks give one clear error naming the file, the key, the line and what is allowed.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/deck.hpp"
#include "io/deck_error.hpp"

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
  // adapt: {max_level: N} alone: stretch trigger at 0.5, damage trigger, interface horizons. Naming any trigger switches to the thesis' explicit form.
  const Deck d = parse_deck(std::string(kGood) + "adapt: {max_level: 1}\n", "good.yaml");
  ASSERT_TRUE(d.adapt.enabled);
  ASSERT_TRUE(d.adapt.stretch_fraction.has_value());
  EXPECT_EQ(*d.adapt.stretch_fraction, kDefaultStretchTrigger);
  EXPECT_TRUE(d.adapt.damage_trigger);
  EXPECT_TRUE(d.adapt.interface_horizon);
  EXPECT_FALSE(d.adapt.energy_fraction.has_value());
  const Deck e = parse_deck(std::string(kGood) + "adapt: {max_level: 1, energy_trigger: 0.5}\n",
                            "good.yaml");
  EXPECT_FALSE(e.adapt.stretch_fraction.has_value());
  EXPECT_FALSE(e.adapt.damage_trigger);
  EXPECT_FALSE(e.adapt.interface_horizon);
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
}

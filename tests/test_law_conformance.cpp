// Every force model through the same checks (PMB, LPS and each registered history law of
// material/bond_laws.cpp): a new law is covered here without editing this file.
//  - momentum: internal forces of a random deformation sum to zero (sum f_i V_i);
//  - energy density of a homogeneous isotropic expansion of the elastic branch equals the
//    classical value at interior nodes (sub-cell quadrature, 2% at m = 3);
//  - a homogeneous deformation leaves interior nodes without force;
//  - thread independence: 1 and 2 threads give the same forces and histories bit for bit;
//  - the energy density of some rows (multi-rate's idle rows) is the whole field's there, bit for
//    bit, and leaves the other rows' values alone.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "input/deck_builder.hpp"
#include "material/bond_law.hpp"
#include "material/force_model.hpp"
#include "setup/build_model.hpp"
#include "solver/internal_forces.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {

struct LawCase {
  std::string formulation;
  std::string pairing = "source_horizon";
};

std::vector<LawCase> every_law() {
  // A history law's stress key is 4e5 Pa (block() below): an onset stretch of 2e-4 to 2.7e-4,
  // below the brittle critical stretch (E = 1e9, G0 = 10, delta = 3 mm: ~1.2e-3 in 2D, ~1.7e-3
  // in 3D, roughly), so that the random deformation below takes bonds past their onset.
  std::vector<LawCase> out{{"pmb"}, {"lps"}};
  for (const BondLaw* law : bond_laws()) out.push_back({std::string(law->name)});
  // Every one also in the dual-horizon form.
  const std::size_t n = out.size();
  for (std::size_t k = 0; k < n; ++k) {
    out.push_back(out[k]);
    out.back().pairing = "dual_horizon";
  }
  return out;
}

Model block(const LawCase& c, int dim, int cells) {
  const std::vector<double> lo(static_cast<std::size_t>(dim), 0.0),
      hi(static_cast<std::size_t>(dim), cells * 1e-3);
  DeckBuilder b;
  b.set("model.dimension", dim)
      .set("model.formulation", c.formulation)
      .set("material.youngs_modulus", 1.0e9)
      .set("material.density", 1000.0)
      .set("material.fracture_energy", 10.0)
      .set("discretization.spacing", 0.001)
      .set("discretization.horizon_factor", 3.0)
      .set("discretization.quadrature", "subcell")
      .set("discretization.body.box.min", lo)
      .set("discretization.body.box.max", hi)
      .set("solver.steps", 1)
      .set("solver.bond_pairing", c.pairing);
  if (c.formulation == "lps") b.set("material.poisson_ratio", 0.3);
  if (const BondLaw* law = find_bond_law(c.formulation)) b.set("material." + std::string(law->stress_key), 4.0e5);
  return build_model(b.build());
}

std::size_t centre_node(const NodeSet& ns, double centre) {
  std::size_t mid = 0;
  double best = INFINITY;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    double r = 0;
    for (int d = 0; d < ns.dim; ++d) r += std::pow(ns.x[d][i] - centre, 2);
    if (r < best) best = r, mid = i;
  }
  return mid;
}

void random_deformation(NodeSet& ns, double amplitude, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (std::size_t i = 0; i < ns.size(); ++i) {
    for (int d = 0; d < ns.dim; ++d) ns.u[d][i] = u(gen);
    ns.sync_current(i);
  }
}

// 4e-6 m random displacements on a 1 mm grid: stretches up to ~8e-3, past every onset and some
// breaking stretches; two passes so that histories and broken bonds take part.
Model deformed_block(const LawCase& c, int dim, unsigned seed) {
  Model m = block(c, dim, dim == 3 ? 8 : 14);
  random_deformation(m.nodes, 4e-6, seed);
  internal_forces(m, true);
  random_deformation(m.nodes, 2e-6, seed + 1);
  internal_forces(m, true);
  return m;
}

class Conformance : public ::testing::TestWithParam<std::tuple<LawCase, int>> {};

TEST_P(Conformance, RandomDeformationForcesSumToZero) {
  const auto& [c, dim] = GetParam();
  Model m = deformed_block(c, dim, 7);
  const NodeSet& ns = m.nodes;
  for (int d = 0; d < dim; ++d) {
    double sum = 0, scale = 0;
    for (std::size_t i = 0; i < ns.size(); ++i) {
      sum += ns.f[d][i] * ns.volume[i];
      scale += std::abs(ns.f[d][i] * ns.volume[i]);
    }
    ASSERT_GT(scale, 0.0);
    EXPECT_LT(std::abs(sum) / scale, 1e-12) << c.formulation << " component " << d;
  }
}

TEST_P(Conformance, IsotropicExpansionOfTheElasticBranchIsClassicalAndBalanced) {
  const auto& [c, dim] = GetParam();
  const int cells = dim == 3 ? 11 : 15;
  Model m = block(c, dim, cells);
  NodeSet& ns = m.nodes;
  const double eps = 1e-5;  // below every onset
  const double e[3][3] = {{eps, 0, 0}, {0, eps, 0}, {0, 0, eps}};
  test::apply_homogeneous_strain(ns, e);
  std::vector<double> W;
  internal_forces(m, true, nullptr, &W);
  const std::size_t mid = centre_node(ns, 0.5 * cells * 1e-3);
  // Sub-cell partial volumes at m = 3 reach the classical value within 2% (issue 2's
  // acceptance, tests/test_energy_density.cpp).
  const double nu = c.formulation == "lps" ? 0.3 : bond_based_poisson(dim, PlaneCondition::Stress);
  const double classical = dim == 3 ? 1.5 * 1e9 / (1 - 2 * nu) * eps * eps
                                    : 1e9 / (1 - nu) * eps * eps;  // plane stress
  EXPECT_NEAR(W[mid] / classical, 1.0, 0.02) << c.formulation;
  // Balanced to round-off: against the size of one bond force times the family size. A stretch
  // of 1e-5 formed from positions carries a relative round-off of about 1e-11.
  double family_volume = 0;
  for (std::uint64_t k = m.bonds.begin(mid); k < m.bonds.end(mid); ++k)
    family_volume += ns.volume[m.bonds.neighbor[k]];
  const double f_scale = m.nodes.micromodulus[mid] * eps * family_volume;
  for (int d = 0; d < dim; ++d) EXPECT_LT(std::abs(ns.f[d][mid]), 1e-9 * f_scale);
}

TEST_P(Conformance, ThreadCountChangesNoBit) {
  const auto& [c, dim] = GetParam();
  auto run = [&](int threads) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    Model m = block(c, dim, dim == 3 ? 8 : 14);
    std::vector<double> W;
    std::size_t broken = 0;
    for (unsigned pass = 0; pass < 3; ++pass) {
      random_deformation(m.nodes, 3e-6 * (pass + 1), 11 + pass);
      broken += internal_forces(m, true, nullptr, &W);
    }
    omp_set_num_threads(saved);
    std::vector<double> out(W);
    for (int d = 0; d < dim; ++d) out.insert(out.end(), m.nodes.f[d].begin(), m.nodes.f[d].end());
    out.insert(out.end(), m.bonds.state.begin(), m.bonds.state.end());
    out.push_back(static_cast<double>(broken));
    return out;
  };
  const std::vector<double> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k], two[k]) << c.formulation << " entry " << k;
}

TEST_P(Conformance, EnergyOfSomeRowsIsTheWholeFieldsThere) {
  const auto& [c, dim] = GetParam();
  Model m = deformed_block(c, dim, 21);
  std::vector<double> whole;
  material_energy_density(m.nodes, m.bonds, material_context(m), whole);
  const std::size_t n = m.nodes.size();
  std::vector<std::uint32_t> rows;
  for (std::size_t i = 0; i < n; i += 3) rows.push_back(static_cast<std::uint32_t>(i));
  std::vector<double> part(n, -1.0);  // a value no density takes
  material_energy_density(m.nodes, m.bonds, material_context(m), part, &rows);
  ASSERT_EQ(part.size(), n);
  double largest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    largest = std::max(largest, whole[i]);
    if (i % 3 == 0) ASSERT_EQ(part[i], whole[i]) << c.formulation << " row " << i;
    else ASSERT_EQ(part[i], -1.0) << c.formulation << " row " << i << " was not asked for";
  }
  EXPECT_GT(largest, 0.0);
}

std::string case_name(const ::testing::TestParamInfo<std::tuple<LawCase, int>>& p) {
  const LawCase& c = std::get<0>(p.param);
  return c.formulation + (c.pairing == "dual_horizon" ? "_dual_" : "_") +
         std::to_string(std::get<1>(p.param)) + "d";
}

INSTANTIATE_TEST_SUITE_P(EveryLaw, Conformance,
                         ::testing::Combine(::testing::ValuesIn(every_law()), ::testing::Values(2, 3)),
                         case_name);

}  // namespace

// Surface correction (issue 3): a node near a free surface must have the classical strain-energy
// density. The energy method (Madenci & Oterkus) fixes the two axial uniaxial strains only; the
// moment-matching method fixes every homogeneous strain, shear included, for nodes whose families
// are symmetric about the axes. Strain energies are computed with the PMB energy density
// (thesis Eq. 2.14) under u = eps . x and compared with W = eps : C : eps / 2 of the isotropic
// material with the bond-based Poisson ratio.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "adapt/refine.hpp"
#include "input/deck_builder.hpp"
#include "material/pmb.hpp"
#include "studies/plate_error_profiles.hpp"
#include "run/static_run.hpp"
#include "setup/build_model.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {

using Strain = std::array<std::array<double, 3>, 3>;

double classical_energy(int dim, PlaneCondition plane, double E, const Strain& e) {
  const double nu = bond_based_poisson(dim, plane);
  // Plane stress acts as 2D with lambda* = 2 lambda mu / (lambda + 2 mu).
  double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = E / (2 * (1 + nu));
  if (dim == 2 && plane == PlaneCondition::Stress) lambda = 2 * lambda * mu / (lambda + 2 * mu);
  double tr = 0, ee = 0;
  for (int a = 0; a < dim; ++a) {
    tr += e[a][a];
    for (int b = 0; b < dim; ++b) ee += e[a][b] * e[a][b];
  }
  return 0.5 * lambda * tr * tr + mu * ee;
}

std::vector<Strain> strain_states(int dim) {
  const double s = 1e-4;
  std::vector<Strain> out;
  for (int a = 0; a < dim; ++a) {  // uniaxial along each axis
    Strain e{};
    e[a][a] = s;
    out.push_back(e);
  }
  for (int a = 0; a < dim; ++a)  // simple shear in every plane
    for (int b = a + 1; b < dim; ++b) {
      Strain e{};
      e[a][b] = e[b][a] = 0.5 * s;
      out.push_back(e);
    }
  Strain iso{};  // isotropic expansion
  for (int a = 0; a < dim; ++a) iso[a][a] = s;
  out.push_back(iso);
  return out;
}

struct Worst {
  double axial = 0, other = 0;  // worst |W/W_classical - 1| over axial / shear+isotropic states
};

// A plate (2D, IPA-Hybrid) or block (3D, sub-cell volumes) with `cells` cells a side; the probed
// nodes lie on the mid-line of one face at depths 0 .. 4 cells (families symmetric about the
// face normal's plane), plus the centre.
Worst surface_errors(int dim, const std::string& correction, int cells) {
  const double dx = 1e-3, E = 1e9;
  DeckBuilder d;
  d.set("model.dimension", dim);
  if (dim == 2) d.set("model.plane", "stress");
  d.set("material.youngs_modulus", 1.0e9)
      .set("material.density", 1000.0)
      .set("discretization.spacing", 0.001)
      .set("discretization.horizon_factor", 3.015)
      .set("discretization.registration", "node_on_edge")
      .set("discretization.quadrature", dim == 2 ? "ipa_hybrid" : "subcell")
      .set("discretization.surface_correction", correction)
      .set("discretization.body.box.min", std::vector<double>(dim, 0.0))
      .set("discretization.body.box.max", std::vector<double>(dim, cells * dx))
      .set("damage.enabled", false)
      .set("solver.steps", 1);
  Model m = build_model(d.build("block"));
  NodeSet& ns = m.nodes;
  const double mid = 0.5 * cells * dx;
  std::vector<std::size_t> probes;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    bool on_line = true;  // x = depth from the x = 0 face, other coordinates at the middle
    for (int d = 1; d < dim; ++d) on_line = on_line && std::abs(ns.x[d][i] - mid) < 1e-9;
    if (on_line && (ns.x[0][i] < 4.5 * dx || std::abs(ns.x[0][i] - mid) < 1e-9)) probes.push_back(i);
  }
  EXPECT_EQ(probes.size(), 6u);
  Worst w;
  const auto states = strain_states(dim);
  for (std::size_t s = 0; s < states.size(); ++s) {
    const Strain& e = states[s];
    for (std::size_t i = 0; i < ns.size(); ++i) {
      for (int a = 0; a < dim; ++a) {
        ns.u[a][i] = 0;
        for (int b = 0; b < dim; ++b) ns.u[a][i] += e[a][b] * ns.x[b][i];
      }
      ns.sync_current(i);
    }
    std::vector<double> W;
    pmb_energy_density(ns, m.bonds, InfluenceShape::Constant, W);
    const double Wc = classical_energy(dim, dim == 2 ? PlaneCondition::Stress : PlaneCondition::None, E, e);
    for (std::size_t i : probes) {
      const double err = std::abs(W[i] / Wc - 1);
      (s < static_cast<std::size_t>(dim) ? w.axial : w.other) =
          std::max(s < static_cast<std::size_t>(dim) ? w.axial : w.other, err);
    }
  }
  return w;
}

}  // namespace

TEST(SurfaceCorrection, MomentMatchingGivesClassicalEnergyForEveryStrainNearA2DEdge) {
  const Worst none = surface_errors(2, "false", 24);
  const Worst energy = surface_errors(2, "energy", 24);
  const Worst moments = surface_errors(2, "moments", 24);
  std::printf("2D worst |W/W_cl - 1|: none %.4f/%.4f, energy %.4f/%.4f, moments %.4f/%.4f "
              "(axial/shear+isotropic)\n", none.axial, none.other, energy.axial, energy.other,
              moments.axial, moments.other);
  EXPECT_GT(none.axial, 0.3);      // an edge node misses about half its family
  EXPECT_GT(energy.other, 0.05);   // the energy method leaves shear and coupling off
  // ... but cuts the axial deficit it is built on (measured to 0.49 of none in 2D, 0.56 in 3D)
  EXPECT_LT(energy.axial, 0.6 * none.axial);
  EXPECT_LT(moments.axial, 1e-3);  // fixed point of the averaged factors: exact moments
  EXPECT_LT(moments.other, 1e-3);
}

TEST(SurfaceCorrection, MomentMatchingGivesClassicalEnergyForEveryStrainNearA3DFace) {
  const Worst none = surface_errors(3, "false", 12);
  const Worst energy = surface_errors(3, "energy", 12);
  const Worst moments = surface_errors(3, "moments", 12);
  std::printf("3D worst |W/W_cl - 1|: none %.4f/%.4f, energy %.4f/%.4f, moments %.4f/%.4f\n",
              none.axial, none.other, energy.axial, energy.other, moments.axial, moments.other);
  EXPECT_GT(energy.other, 0.05);
  EXPECT_LT(energy.axial, 0.6 * none.axial);
  EXPECT_LT(moments.axial, 1e-3);
  EXPECT_LT(moments.other, 1e-3);
}

// Thesis 4.1 plate, uniform grid: with surface correction the mean relative error of u_x on the
// horizontal centre line is below 2% (issue 3 acceptance; the thesis reports about 2%).
TEST(SurfaceCorrection, TensionPlateCentreLineErrorBelowTwoPercent) {
  double mean_ex[2];
  const char* methods[2] = {"energy", "moments"};
  for (int k = 0; k < 2; ++k) {
    RunOptions ro;
    ro.write_files = false;
    ro.quiet = true;
    const RunResult r =
        run_static(tension_plate_deck(methods[k], "source_horizon", 0), ro);
    mean_ex[k] = plate_errors(r.model.nodes, 200e6, 200e9, 1.0 / 3.0).mean_ex(0, 1);
  }
  std::printf("plate mean |e(u_x)|: energy %.3f%%, moments %.3f%%\n", mean_ex[0], mean_ex[1]);
  EXPECT_LT(mean_ex[1], 2.0);
  EXPECT_LT(mean_ex[1], mean_ex[0]);
}

namespace {

// A 24 x 16 mm plate with `correction`, refined twice around (3, 8) mm on its left edge (level 1,
// then level 2 inside it) and once in its middle: each event corrects its window again.
Model refined_plate(const std::string& correction, bool global) {
  if (global) setenv("PERIADAPT_GLOBAL_REBUILD", "1", 1);
  else unsetenv("PERIADAPT_GLOBAL_REBUILD");
  DeckBuilder d;
  d.set("model.dimension", 2)
      .set("model.plane", "stress")
      .set("material.youngs_modulus", 1.0e9)
      .set("material.density", 1000.0)
      .set("discretization.spacing", 0.001)
      .set("discretization.surface_correction", correction)
      .set("discretization.body.box.min", std::vector<double>{0.0, 0.0})
      .set("discretization.body.box.max", std::vector<double>{0.024, 0.016})
      .set("damage.enabled", false)
      .set("solver.steps", 1);
  Model m = build_model(d.build("plate"));
  m.window_surface_correction = true;  // as the adaptor sets it for a run's events
  test::refine_zones(m, {{0.003, 0.008, 0.003, 0}, {0.002, 0.008, 0.0012, 1}, {0.015, 0.008, 0.002, 0}});
  unsetenv("PERIADAPT_GLOBAL_REBUILD");
  return m;
}

// Worst |W / W_classical - 1| over the strain states, over the active nodes at least 4 mm
// (a coarse horizon and a cell) from two faces at once (a corner's family cannot take the bulk
// moments with positive factors).
double worst_energy_error(Model& m) {
  NodeSet& ns = m.nodes;
  const double E = 1e9;
  double worst = 0;
  for (const Strain& e : strain_states(2)) {
    for (std::size_t i = 0; i < ns.size(); ++i) {
      for (int a = 0; a < 2; ++a) ns.u[a][i] = e[a][0] * ns.x[0][i] + e[a][1] * ns.x[1][i];
      ns.sync_current(i);
    }
    std::vector<double> W;
    pmb_energy_density(ns, m.bonds, InfluenceShape::Constant, W);
    const double Wc = classical_energy(2, PlaneCondition::Stress, E, e);
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      const double x = ns.x[0][i], y = ns.x[1][i];
      const bool near_x = x < 0.004 || x > 0.020, near_y = y < 0.004 || y > 0.012;
      if (near_x && near_y) continue;
      worst = std::max(worst, std::abs(W[i] / Wc - 1));
    }
  }
  return worst;
}

// Largest |beta_ij / beta_ji - 1| over the pairs whose ends have the same horizon and spacing
// (their quadrature factors are equal, so a symmetric correction leaves them equal).
double worst_asymmetry(const Model& m) {
  const NodeSet& ns = m.nodes;
  const BondFamilies& bf = m.bonds;
  double worst = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      if (ns.horizon[j] != ns.horizon[i] || ns.spacing[j] != ns.spacing[i]) continue;
      for (std::uint64_t h = bf.begin(j); h < bf.end(j); ++h)
        if (bf.neighbor[h] == i)
          worst = std::max(worst, std::abs(static_cast<double>(bf.beta[k]) / bf.beta[h] - 1));
    }
  return worst;
}

// Largest ratio of a row's stiffness sum, sum |beta_ij| V_j / |xi_ij| (what the stable time
// step reads), in `a` over the same row in `b` (the same nodes and rows).
double worst_row_stiffness_ratio(const Model& a, const Model& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    if (!(a.nodes.flags[i] & kActive)) continue;
    double sa = 0, sb = 0;
    for (std::uint64_t k = a.bonds.begin(i), h = b.bonds.begin(i); k < a.bonds.end(i); ++k, ++h) {
      const double v = a.nodes.volume[a.bonds.neighbor[k]];
      sa += std::abs(static_cast<double>(a.bonds.beta[k])) * v / a.bonds.length(k);
      sb += std::abs(static_cast<double>(b.bonds.beta[h])) * v / b.bonds.length(h);
    }
    if (sb > 0) worst = std::max(worst, sa / sb);
  }
  return worst;
}

}  // namespace

// The energy method's factors come from each node's own family and its neighbours', so an event
// that corrects its window and the ring around it gives every bond the factor a correction of
// the whole model gives.
TEST(SurfaceCorrection, EnergyMethodOfAnEventsWindowEqualsTheWholeModels) {
  const Model local = refined_plate("energy", false), global = refined_plate("energy", true);
  ASSERT_EQ(local.nodes.size(), global.nodes.size());
  std::size_t compared = 0;
  double worst = 0;
  for (std::size_t i = 0; i < local.nodes.size(); ++i) {
    const BondFamilies &a = local.bonds, &b = global.bonds;
    ASSERT_EQ(a.end(i) - a.begin(i), b.end(i) - b.begin(i)) << i;
    for (std::uint64_t k = a.begin(i), h = b.begin(i); k < a.end(i); ++k, ++h) {
      ASSERT_EQ(a.neighbor[k], b.neighbor[h]);
      worst = std::max(worst, std::abs(static_cast<double>(a.beta[k]) / b.beta[h] - 1));
      ++compared;
    }
  }
  std::printf("energy method, %zu bonds: largest relative difference %.3g\n", compared, worst);
  EXPECT_GT(compared, 10000u);
  EXPECT_LT(worst, 1e-6);  // float factors
}

// The moments method's fixed point is not unique: an event's window, refitted from its old
// factors, ends with other factors than a correction from scratch, but every node that can take
// the bulk moments has them, and so the classical energy of every homogeneous strain.
TEST(SurfaceCorrection, MomentsMethodOfAnEventsWindowGivesEveryNodeTheBulkMoments) {
  Model none = refined_plate("false", false);
  Model local = refined_plate("moments", false), global = refined_plate("moments", true);
  const double e_none = worst_energy_error(none), e_local = worst_energy_error(local),
               e_global = worst_energy_error(global);
  std::printf("moments, worst |W/W_cl - 1| away from corners: none %.4f, window %.2e, whole "
              "model %.2e\n", e_none, e_local, e_global);
  EXPECT_GT(e_none, 0.3);
  EXPECT_LT(e_global, 1e-3);
  EXPECT_LT(e_local, 1e-3);
  const double a_local = worst_asymmetry(local), a_global = worst_asymmetry(global);
  std::printf("largest |beta_ij / beta_ji - 1| of like pairs: window %.2e, whole model %.2e\n",
              a_local, a_global);
  EXPECT_LT(a_global, 1e-6);  // float factors
  EXPECT_LT(a_local, 1e-6);
  // The refits start from the quadrature's factors, as the whole model's correction does, and
  // differ from it only through the bonds held at the ring's outer edge: each row's stiffness
  // sum (what sets the stable step) stays within 2% of the whole model's (measured 1.006;
  // refits started from the old corrected factors gave 1.108 here, and a stable step 27% short
  // after 15 events of an LPS plate).
  const double k_ratio = worst_row_stiffness_ratio(local, global);
  std::printf("largest row stiffness sum |beta| V / L, window over whole model: %.4f\n", k_ratio);
  EXPECT_LT(k_ratio, 1.02);
}

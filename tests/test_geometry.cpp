// Geometry primitives: distances from points to hole shapes (used to report how close a crack
// tip came to a hole), checked against hand-computed values.
#include <gtest/gtest.h>

#include "core/geometry.hpp"
#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "test_helpers.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

using namespace periadapt;

TEST(Geometry, DistanceToShapeIsZeroInsideAndEuclideanOutside) {
  Shape disk;
  disk.kind = Shape::Kind::Disk;
  disk.center = {0.02, 0.029, 0.0};
  disk.radius = 0.005;
  EXPECT_DOUBLE_EQ(disk.distance_to_shape({0.02, 0.03, 0.0}), 0.0);
  EXPECT_NEAR(disk.distance_to_shape({0.02, 0.019, 0.0}), 0.005, 1e-15);     // 10 mm below the centre
  EXPECT_NEAR(disk.distance_to_shape({0.023, 0.025, 0.0}), 0.0, 1e-15);      // on the rim (3-4-5)
  EXPECT_NEAR(disk.distance_to_shape({0.026, 0.021, 0.0}), 0.005, 1e-15);    // 6-8-10 from the centre

  Shape box;
  box.kind = Shape::Kind::Box;
  box.box.lo = {0, 0, 0};
  box.box.hi = {1, 2, 3};
  EXPECT_DOUBLE_EQ(box.distance_to_shape({0.5, 1, 1}), 0.0);
  EXPECT_DOUBLE_EQ(box.distance_to_shape({4, 6, 1}), 5.0);  // 3-4-5 from the corner (1, 2)

  Shape sphere;
  sphere.kind = Shape::Kind::Sphere;
  sphere.center = {1, 1, 1};
  sphere.radius = 1;
  EXPECT_DOUBLE_EQ(sphere.distance_to_shape({1, 1, 4}), 2.0);

  Shape cyl;  // along z: the axial coordinate does not count
  cyl.kind = Shape::Kind::Cylinder;
  cyl.axis = 2;
  cyl.radius = 0.5;
  EXPECT_DOUBLE_EQ(cyl.distance_to_shape({3, 4, 100}), 4.5);
}

// Polygon bodies (2D): the nodes are the cell centres inside the outline, each with its full cell
// volume. An outline along cell edges gives the area exactly; any other misses only cells cut by
// the outline, at most dx^2 each, and at most sqrt(2) P / dx + 4 cells lie on a perimeter P.
TEST(Geometry, PolygonBodyVolumesSumToItsArea) {
  auto volume = [](const std::vector<std::vector<double>>& polygon) {
    const Model m = build_model(DeckBuilder()
                                    .set("model.dimension", 2)
                                    .set("model.thickness", 0.01)
                                    .set("material.youngs_modulus", 72.0e9)
                                    .set("material.density", 2440.0)
                                    .set("discretization.spacing", 1.0e-3)
                                    .set("discretization.horizon_factor", 3.0)
                                    .set("discretization.body.polygon", polygon)
                                    .set("damage.enabled", false)
                                    .set("solver.steps", 1)
                                    .build("polygon body"));
    double v = 0;
    for (double x : m.nodes.volume) v += x;
    return v / 0.01;
  };
  // L-shape on cell edges: 0.04 x 0.04 less its 0.02 x 0.02 corner.
  EXPECT_NEAR(volume({{0, 0}, {0.04, 0}, {0.04, 0.02}, {0.02, 0.02}, {0.02, 0.04}, {0, 0.04}}),
              0.04 * 0.04 * 0.75, 1e-15);
  // A triangle across the lattice (and listed clockwise).
  const double area = 0.5 * 0.0503 * 0.0371, perimeter = 0.0503 + 0.0371 + std::hypot(0.0503, 0.0371);
  const double dx = 1e-3;
  EXPECT_NEAR(volume({{0.0002, 0.0004}, {0.0002, 0.0375}, {0.0505, 0.0004}}), area,
              std::sqrt(2.0) * perimeter * dx + 4 * dx * dx);
}

// Holes take any region: an L-shaped polygon on cell edges removes exactly its cells (2D), a box
// and a sphere in 3D remove the cells whose centres they hold.
TEST(Geometry, PolygonAndBoxHolesRemoveTheirCells) {
  // A plate or block 0.1 m a side.
  auto volume = [](int dim, const std::vector<DeckBuilder>& holes) {
    DeckBuilder d;
    d.set("model.dimension", dim);
    if (dim == 2) d.set("model.thickness", 0.01);
    d.set("material.youngs_modulus", 72.0e9)
        .set("material.density", 2440.0)
        .set("discretization.spacing", 0.01)
        .set("discretization.body.box.min", std::vector<double>(dim, 0.0))
        .set("discretization.body.box.max", std::vector<double>(dim, 0.1))
        .set("discretization.holes", std::vector<std::string>{})  // [] when there are none
        .set("damage.enabled", false)
        .set("solver.steps", 1);
    for (const DeckBuilder& hole : holes) d.append("discretization.holes", hole);
    const Model m = build_model(d.build("holed body"));
    double v = 0;
    for (double x : m.nodes.volume) v += x;
    return v;
  };
  const std::vector<std::vector<double>> outline = {{0.02, 0.02}, {0.06, 0.02}, {0.06, 0.04},
                                                    {0.04, 0.04}, {0.04, 0.07}, {0.02, 0.07}};
  const double plate = volume(2, {});
  const double holed = volume(2, {DeckBuilder().set("polygon", outline)});
  EXPECT_NEAR((plate - holed) / 0.01, 0.04 * 0.02 + 0.02 * 0.03, 1e-15);
  const double block = volume(3, {});
  const double cut = volume(3, {test::box({0.02, 0.02, 0.02}, {0.05, 0.04, 0.1})});
  EXPECT_NEAR(block - cut, 0.03 * 0.02 * 0.08, 1e-15);
}

// A point-cloud body keeps its nodes' positions, order and volumes as written (volumes need not
// be the cell's), with the deck's spacing; its bounding box is the points' cells'.
TEST(Geometry, PointCloudBodyKeepsItsNodesAsWritten) {
  const std::string file = ::testing::TempDir() + "periadapt_points.csv";
  {
    std::ofstream out(file);
    out << "x,y,z,volume\n0.0,0.0,0.0,2e-9\n0.002,0.0,0.0,1e-9\n0.001,0.003,-0.001,3e-9\n";
  }
  const Model m = build_model(DeckBuilder()
                                  .set("model.dimension", 3)
                                  .set("material.youngs_modulus", 72.0e9)
                                  .set("material.density", 2440.0)
                                  .set("discretization.spacing", 0.001)
                                  .set("discretization.body.points", file)
                                  .set("damage.enabled", false)
                                  .set("solver.steps", 1)
                                  .build("point cloud"));
  ASSERT_EQ(m.nodes.size(), 3u);
  const double expect[3][4] = {{0, 0, 0, 2e-9}, {0.002, 0, 0, 1e-9}, {0.001, 0.003, -0.001, 3e-9}};
  for (std::size_t i = 0; i < 3; ++i) {
    for (int d = 0; d < 3; ++d) EXPECT_EQ(m.nodes.x[d][i], expect[i][d]);
    EXPECT_EQ(m.nodes.volume[i], expect[i][3]);
    EXPECT_EQ(m.nodes.spacing[i], 0.001);
  }
  EXPECT_DOUBLE_EQ(m.body.lo[1], -0.0005);
  EXPECT_DOUBLE_EQ(m.body.hi[1], 0.0035);
  EXPECT_DOUBLE_EQ(m.body.lo[2], -0.0015);
  std::remove(file.c_str());
}

TEST(Geometry, PolygonRegionContainsAndDistance) {
  Shape s;
  s.kind = Shape::Kind::Polygon;
  s.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  EXPECT_TRUE(s.contains({0.5, 1.5, 0}));
  EXPECT_FALSE(s.contains({1.5, 1.5, 0}));        // the cut-away corner
  EXPECT_FALSE(s.contains({2.0 + 1e-6, 0.5, 0}));
  EXPECT_TRUE(s.contains({2.0 + 1e-6, 0.5, 0}, 1e-5));  // within the tolerance of an edge
  EXPECT_FALSE(s.contains({1.99, 0.5, 0}, -0.02));      // negative tolerance narrows it
  EXPECT_DOUBLE_EQ(s.distance_to_shape({1.5, 1.5, 0}), 0.5);
  EXPECT_DOUBLE_EQ(s.distance_to_shape({3, 0.5, 0}), 1.0);
  EXPECT_EQ(s.distance_to_shape({0.5, 0.5, 0}), 0.0);
}

TEST(Geometry, BondCrossingDecidesMirrorImagesAlike) {
  // The crack memory cuts a child's bond where it crosses the short facet left by a broken bond
  // (mid-point +- a quarter spacing across it). On a lattice a facet's end often lies exactly on
  // a bond, where the exact orientation is 0 and the computed one is round-off; mirror images
  // (y -> L - y, whose coordinates differ in their last bits) then decided differently, and a
  // mirror-symmetric plate cracked on one side only. Every bond and facet of a patch of a
  // 0.5 mm lattice against its mirror image about y = 15 mm: the same decision for all.
  const double h = 0.5e-3, L = 0.03;
  auto node = [&](int i, int j, bool mirrored) {
    const double y = (j + 0.5) * h;
    return Vec3{(i + 0.5) * h, mirrored ? L - y : y, 0.0};
  };
  auto facet = [&](const Vec3& xi, const Vec3& xj, Vec3& a, Vec3& b) {
    const Vec3 mid = scale(add(xi, xj), 0.5), e = scale(sub(xj, xi), 1.0 / norm(sub(xj, xi)));
    const Vec3 t{-e[1] * 0.25 * h, e[0] * 0.25 * h, 0.0};
    a = sub(mid, t);
    b = add(mid, t);
  };
  std::size_t crossings = 0, disagreements = 0, total = 0;
  for (int i0 = 0; i0 < 4; ++i0)
    for (int j0 = 14; j0 < 20; ++j0)
      for (int di = -2; di <= 2; ++di)
        for (int dj = -2; dj <= 2; ++dj) {
          if (!di && !dj) continue;
          for (int fi = 0; fi < 4; ++fi)
            for (int fj = 14; fj < 20; ++fj)
              for (int ei = -2; ei <= 2; ++ei)
                for (int ej = -2; ej <= 2; ++ej) {
                  if (!ei && !ej) continue;
                  bool cut[2];
                  for (const bool mirrored : {false, true}) {
                    Vec3 a, b;
                    facet(node(fi, fj, mirrored), node(fi + ei, fj + ej, mirrored), a, b);
                    cut[mirrored] = bond_crosses_segment<true>(node(i0, j0, mirrored),
                                                               node(i0 + di, j0 + dj, mirrored), a, b);
                  }
                  ++total;
                  crossings += cut[0];
                  disagreements += cut[0] != cut[1];
                }
        }
  EXPECT_GT(crossings, total / 100);  // the patch does cross facets
  EXPECT_EQ(disagreements, 0u) << "of " << total;
}

TEST(Geometry, BondCrossingAQuadDecidesMirrorImagesAlike) {
  // The 3D crack memory's facets: a square a half spacing wide across the broken bond at its
  // mid-point. A lattice node can lie exactly in a facet's plane; mirror images about y = 15 mm
  // must still decide alike (before the sides were snapped: 230 of 623,376 pairs differed).
  const double h = 0.5e-3, L = 0.03;
  auto node = [&](int i, int j, int k, bool mirrored) {
    const double y = (j + 0.5) * h;
    return Vec3{(i + 0.5) * h, mirrored ? L - y : y, (k + 0.5) * h};
  };
  std::size_t crossings = 0, disagreements = 0, total = 0;
  for (int i0 = 0; i0 < 2; ++i0)
    for (int j0 = 14; j0 < 17; ++j0)
      for (int di = -2; di <= 2; ++di)
        for (int dj = -2; dj <= 2; ++dj)
          for (int dk = -1; dk <= 1; ++dk) {
            if (!di && !dj && !dk) continue;
            for (int fi = 0; fi < 2; ++fi)
              for (int fj = 14; fj < 17; ++fj)
                for (int ei = -1; ei <= 1; ++ei)
                  for (int ej = -1; ej <= 1; ++ej)
                    for (int ek = -1; ek <= 1; ++ek) {
                      if (!ei && !ej && !ek) continue;
                      bool cut[2];
                      for (const bool mirrored : {false, true}) {
                        const Vec3 xi = node(fi, fj, 0, mirrored), xj = node(fi + ei, fj + ej, ek, mirrored);
                        const Vec3 mid = scale(add(xi, xj), 0.5);
                        const Vec3 e = scale(sub(xj, xi), 1.0 / norm(sub(xj, xi)));
                        const Vec3 axis = std::abs(e[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
                        Vec3 u = cross(e, axis);
                        u = scale(u, 0.25 * h / norm(u));
                        const Vec3 w = cross(e, u);
                        const std::array<Vec3, 4> quad = {sub(sub(mid, u), w), sub(add(mid, u), w),
                                                          add(add(mid, u), w), add(sub(mid, u), w)};
                        cut[mirrored] = bond_crosses_quad<true>(node(i0, j0, 0, mirrored),
                                                                node(i0 + di, j0 + dj, dk, mirrored), quad);
                      }
                      ++total;
                      crossings += cut[0];
                      disagreements += cut[0] != cut[1];
                    }
          }
  EXPECT_GT(crossings, total / 200);
  EXPECT_EQ(disagreements, 0u) << "of " << total;
}

// Geometry primitives: distances from points to hole shapes (used to report how close a crack
// tip came to a hole), checked against hand-computed values.
#include <gtest/gtest.h>

#include "core/geometry.hpp"

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

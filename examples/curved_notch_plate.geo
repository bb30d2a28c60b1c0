// A 100 x 40 mm plate with a U-notch cut into its left edge at mid-height: a 2 mm wide slot,
// 19 mm long, ending in a semicircle of radius 1 mm (root at x = 20 mm). Lengths in metres.
// Gmsh meshes it when PeriAdapt reads it (examples/gmsh_notched_plate_2d.yaml); the mesh is
// fine along the notch so that its edges follow the arc to 0.1 mm chords.
h = 2.0e-3;
hn = 0.1e-3;
Point(1) = {0, 0, 0, h};
Point(2) = {0.1, 0, 0, h};
Point(3) = {0.1, 0.04, 0, h};
Point(4) = {0, 0.04, 0, h};
Point(5) = {0, 0.021, 0, hn};
Point(6) = {0.019, 0.021, 0, hn};
Point(7) = {0.019, 0.020, 0, hn};
Point(8) = {0.020, 0.020, 0, hn};
Point(9) = {0.019, 0.019, 0, hn};
Point(10) = {0, 0.019, 0, hn};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Circle(6) = {6, 7, 8};
Circle(7) = {8, 7, 9};
Line(8) = {9, 10};
Line(9) = {10, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9};
Plane Surface(1) = {1};

Point(1)={0,0,0,1e-3}; Point(2)={0.01,0,0,1e-3}; Point(3)={0.01,0.01,0,1e-3};Point(4)={0,0.01,0,1e-3};
Line(1)={1,3}; Line(2)={3,2}; Line(3)={2,4}; Line(4)={4,1};
Curve Loop(1)={1,2,3,4}; Plane Surface(1)={1};

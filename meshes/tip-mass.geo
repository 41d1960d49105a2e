// The mueller2023 beam with a node at x = 0.126 m (0.9 L), where tip-mass.prm
// fixes an added mass: 30 elements, tag 1.
//   gmsh -1 tip-mass.geo -format msh41 -o tip-mass.msh
L = 0.14;
Point(1) = {0, 0, 0};
Point(2) = {0.126, 0, 0};
Point(3) = {L, 0, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Transfinite Curve{1} = 28; // 27 elements of 4.67 mm
Transfinite Curve{2} = 4;  // 3 of 4.67 mm
Physical Curve("steel", 1) = {1, 2};

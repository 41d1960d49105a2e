// The mueller2023 beam as a Gmsh mesh: 32 equal line elements along x from 0
// to L = 0.14 m, all with physical tag 1 (one section). uniform.prm gives the
// section; the results equal the generated mesh's to round-off.
//   gmsh -1 uniform.geo -format msh41 -o uniform.msh
L = 0.14;
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Line(1) = {1, 2};
Transfinite Curve{1} = 33; // 33 nodes: 32 elements
Physical Curve("steel", 1) = {1};

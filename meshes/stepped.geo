// A stepped beam: a thicker middle section (tag 2, 0.05 m to 0.09 m) between
// two thin ones (tag 1). stepped.prm gives the sections. An element boundary
// lies at each step, so the FE sections are exact.
//   gmsh -1 stepped.geo -format msh22 -o stepped.msh
L = 0.14;
Point(1) = {0, 0, 0};
Point(2) = {0.05, 0, 0};
Point(3) = {0.09, 0, 0};
Point(4) = {L, 0, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Transfinite Curve{1, 3} = 13; // 12 elements on each thin part
Transfinite Curve{2} = 9;     // 8 on the thick one
Physical Curve("thin", 1) = {1, 3};
Physical Curve("thick", 2) = {2};

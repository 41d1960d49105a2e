// A tapered beam in eight sections of equal length (tags 1 to 8), each of
// four elements; tapered.prm gives their thicknesses, from 1.2 mm at x = 0
// down to 0.85 mm at x = L in equal steps.
//   gmsh -1 tapered.geo -format msh41 -o tapered.msh
L = 0.14;
n = 8;
For i In {0 : n}
  Point(i + 1) = {i * L / n, 0, 0};
EndFor
For i In {1 : n}
  Line(i) = {i, i + 1};
  Transfinite Curve{i} = 5;
  Physical Curve(i) = {i};
EndFor

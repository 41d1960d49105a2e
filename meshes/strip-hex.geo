// Structured all-hexahedral mesh of the clamped-clamped steel strip (SI units):
// x in [0, L] (L = 0.14 m), y in [-b/2, b/2] (b = 0.01404 m), z in [-h/2, h/2]
// (h = 0.001 m); 70 x 4 x 1 linear 8-node hexahedra (280 in all).
// Physical groups: Volume "steel" (1) = the strip; Surface "clamp_left" (1) = x = 0,
// "clamp_right" (2) = x = L, "top" (3) = z = +h/2. No other surface is tagged.
// Produced with gmsh 4.8.4, from meshes/:
//   gmsh -3 strip-hex.geo -format msh41 -o strip-hex.msh
SetFactory("OpenCASCADE");
L = 0.14; b = 0.01404; h = 0.001;
nx = 70; ny = 4; nz = 1;  // elements along x, y, z

Box(1) = {0, -b/2, -h/2, L, b, h};

// Each edge gets the number of nodes of its direction.
e = 1e-6;  // selection tolerance (OpenCASCADE boxes are padded by ~1e-7)
curves[] = Curve{:};
For i In {0 : #curves[] - 1}
  bb[] = BoundingBox Curve{curves[i]};
  If (bb[3] - bb[0] > e)
    Transfinite Curve{curves[i]} = nx + 1;
  ElseIf (bb[4] - bb[1] > e)
    Transfinite Curve{curves[i]} = ny + 1;
  Else
    Transfinite Curve{curves[i]} = nz + 1;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};

Mesh.ElementOrder = 1;
Mesh.SaveAll = 0;

Physical Volume("steel", 1) = {1};
Physical Surface("clamp_left", 1) = Surface In BoundingBox{-e, -b/2-e, -h/2-e, e, b/2+e, h/2+e};
Physical Surface("clamp_right", 2) = Surface In BoundingBox{L-e, -b/2-e, -h/2-e, L+e, b/2+e, h/2+e};
Physical Surface("top", 3) = Surface In BoundingBox{-e, -b/2-e, h/2-e, L+e, b/2+e, h/2+e};

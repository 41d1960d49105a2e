// Structured all-hexahedral mesh of the steel strip held at each end between two
// steel clamp blocks (SI units). Free strip: x in [0, L] (L = 0.14 m), y in [-b/2, b/2]
// (b = 0.01404 m), z in [-h/2, h/2] (h = 0.001 m). Each clamp is one solid block of
// length a = 0.01 m (x in [-a, 0] and [L, L + a]), full strip width, z in
// [-h/2 - t, h/2 + t] (t = 0.003 m), built from three boxes (below / strip layer / above)
// fragmented together with the strip so that the mesh is conforming everywhere.
// Divisions: 70 along the free strip, 5 along each block, 4 across y, 1 through the strip
// layer, 3 through each block layer above/below: 280 + 2 x 5 x 4 x 7 = 560 hexahedra.
// Physical groups: Volume "strip" (1) = free strip, "blocks" (2) = all block volumes;
// Surface "clamp_left" (1) = outer face x = -a, "clamp_right" (2) = outer face x = L + a,
// "top" (3) = strip top z = h/2 for x in [0, L] only. No other surface is tagged.
// Produced with gmsh 4.8.4, from meshes/:
//   gmsh -3 strip-blocks.geo -format msh41 -o strip-blocks.msh
SetFactory("OpenCASCADE");
L = 0.14; b = 0.01404; h = 0.001;
a = 0.01;   // block length along x
t = 0.003;  // block layer thickness above and below the strip
nx = 70; nxb = 5; ny = 4; nz = 1; nzb = 3;  // divisions

Box(1) = {0, -b/2, -h/2, L, b, h};                    // free strip
Box(2) = {-a, -b/2, -h/2 - t, a, b, t};               // left block, below
Box(3) = {-a, -b/2, -h/2,     a, b, h};               // left block, strip layer
Box(4) = {-a, -b/2,  h/2,     a, b, t};               // left block, above
Box(5) = {L, -b/2, -h/2 - t, a, b, t};                // right block, below
Box(6) = {L, -b/2, -h/2,     a, b, h};                // right block, strip layer
Box(7) = {L, -b/2,  h/2,     a, b, t};                // right block, above
BooleanFragments{ Volume{1:7}; Delete; }{}

// Each edge gets the number of nodes of its direction and length.
e = 1e-6;  // selection tolerance (OpenCASCADE boxes are padded by ~1e-7)
curves[] = Curve{:};
For i In {0 : #curves[] - 1}
  bb[] = BoundingBox Curve{curves[i]};
  dx = bb[3] - bb[0]; dy = bb[4] - bb[1]; dz = bb[5] - bb[2];
  If (dx > e)
    If (dx > (L + a) / 2)
      Transfinite Curve{curves[i]} = nx + 1;
    Else
      Transfinite Curve{curves[i]} = nxb + 1;
    EndIf
  ElseIf (dy > e)
    Transfinite Curve{curves[i]} = ny + 1;
  ElseIf (dz > (h + t) / 2)
    Transfinite Curve{curves[i]} = nzb + 1;
  Else
    Transfinite Curve{curves[i]} = nz + 1;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};

Mesh.ElementOrder = 1;
Mesh.SaveAll = 0;

strip[] = Volume In BoundingBox{-e, -b/2-e, -h/2-e, L+e, b/2+e, h/2+e};
blocks[] = Volume{:};
blocks[] -= strip[];
Physical Volume("strip", 1) = strip[];
Physical Volume("blocks", 2) = blocks[];
Physical Surface("clamp_left", 1) = Surface In BoundingBox{-a-e, -b/2-e, -h/2-t-e, -a+e, b/2+e, h/2+t+e};
Physical Surface("clamp_right", 2) = Surface In BoundingBox{L+a-e, -b/2-e, -h/2-t-e, L+a+e, b/2+e, h/2+t+e};
Physical Surface("top", 3) = Surface In BoundingBox{-e, -b/2-e, h/2-e, L+e, b/2+e, h/2+e};

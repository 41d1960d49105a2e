#!/usr/bin/env python3
"""Writes strip-hex-abaqus.inp: the mueller2023 strip (L x b x h =
0.14 x 0.01404 x 0.001 m) as 70 x 4 x 1 linear hexahedra (C3D8), in the
layout of an Abaqus/CAE input deck (a part with node and element blocks,
element sets, element-based surfaces and a solid section).

deal.II's Abaqus reader takes the boundary id of a surface from the number in
its name (SS1 -> 1) and the material id of an element set from the material
its *Solid Section assigns (Material-1 -> 1), so groups are given by number
in the scene (strip-hex-abaqus.prm):
  surface SS1 = the face x = 0 (clamped), SS2 = x = L (clamped),
  SS3 = z = +h/2 (where statics' line load presses), Material-1 = the strip.

Usage, from meshes/:  python3 strip-hex-abaqus.py > strip-hex-abaqus.inp
"""

L, b, h = 0.14, 0.01404, 0.001
nx, ny, nz = 70, 4, 1


def node(i, j, k):
    """1-based node number of grid point (i, j, k)."""
    return 1 + i + (nx + 1) * (j + (ny + 1) * k)


def element(i, j, k):
    """1-based element number of cell (i, j, k)."""
    return 1 + i + nx * (j + ny * k)


def numbers(values, per_line=16):
    values = list(values)
    return "\n".join(", ".join(str(v) for v in values[s:s + per_line]) for s in range(0, len(values), per_line))


lines = ["*Heading", "** mueller2023 strip, 70 x 4 x 1 C3D8, SI units (m); written by strip-hex-abaqus.py",
         "*Part, name=Strip", "*Node"]
for k in range(nz + 1):
    for j in range(ny + 1):
        for i in range(nx + 1):
            lines.append(f"{node(i, j, k)}, {L * i / nx:.10g}, {-b / 2 + b * j / ny:.10g}, {-h / 2 + h * k / nz:.10g}")
# C3D8: nodes 1-4 counter-clockwise on the face z-, 5-8 above them; faces
# S1 (1234, z-), S2 (5678, z+), S3 (1265, y-), S4 (2376, x+), S5 (3487, y+),
# S6 (4158, x-).
lines.append("*Element, type=C3D8")
for k in range(nz):
    for j in range(ny):
        for i in range(nx):
            corners = [node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k)]
            corners += [node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)]
            lines.append(f"{element(i, j, k)}, " + ", ".join(str(c) for c in corners))
lines += ["*Elset, elset=Set-Strip, generate", f"1, {nx * ny * nz}, 1"]
faces = {"SS1": ("S6", [element(0, j, k) for k in range(nz) for j in range(ny)]),
         "SS2": ("S4", [element(nx - 1, j, k) for k in range(nz) for j in range(ny)]),
         "SS3": ("S2", [element(i, j, nz - 1) for j in range(ny) for i in range(nx)])}
for name, (side, elements) in faces.items():
    lines += [f"*Elset, elset=_{name}_{side}, internal", numbers(elements)]
for name, (side, elements) in faces.items():
    lines += [f"*Surface, type=ELEMENT, name={name}", f"_{name}_{side}, {side}"]
lines += ["** Section: the strip", "*Solid Section, elset=Set-Strip, material=Material-1", ",", "*End Part",
          "*Material, name=Material-1", "*Density", "7683.", "*Elastic", "2.1e+11, 0.3"]
print("\n".join(lines))

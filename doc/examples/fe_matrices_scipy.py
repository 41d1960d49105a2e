"""The FE beam's matrices handed to SciPy.

Takes the mass and stiffness matrices of the scene's FE beam as
scipy.sparse matrices (beamslider.FEBeam), keeps the DoFs the bending
modes leave free, solves the generalised eigenproblem K φ = ω² M φ with
SciPy's eigsh (shift-invert about 0) and compares the frequencies with
FEBeam.modes (the library's own eigensolver). Then it checks one property
of the nonlinear beam that the matrices alone cannot show: the tangent at
a deflected state is stiffer than the linear stiffness (bending–stretching).

    PYTHONPATH=build/python python3 doc/examples/fe_matrices_scipy.py --output out
"""
import argparse
import os
import sys

import numpy as np
import scipy.sparse.linalg

import beamslider

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default="fe_matrices_scipy", help="folder for the table of frequencies")
parser.add_argument("--modes", type=int, default=7, help="number of modes")
args = parser.parse_args()
os.makedirs(args.output, exist_ok=True)

beam = beamslider.FEBeam("mueller2023")
free = beam.free_dofs()
K = beam.stiffness()[free][:, free].tocsc()
M = beam.mass()[free][:, free].tocsc()
print(f"FE beam: {beam.n_dofs} DoFs, {len(free)} free for bending; K and M with {K.nnz} and {M.nnz} entries")

eigenvalues = np.sort(scipy.sparse.linalg.eigsh(K, k=args.modes, M=M, sigma=0, return_eigenvectors=False))
scipy_hz = np.sqrt(eigenvalues) / (2 * np.pi)
own_hz, shapes = beam.modes(args.modes)
worst = np.max(np.abs(scipy_hz - own_hz) / own_hz)

table = os.path.join(args.output, "frequencies.csv")
with open(table, "w", encoding="utf-8") as f:
    f.write("mode,febeam_hz,scipy_eigsh_hz,relative_difference\n")
    for k, (a, b) in enumerate(zip(own_hz, scipy_hz), start=1):
        f.write(f"{k},{a:.12g},{b:.12g},{abs(a - b) / a:.3e}\n")
        print(f"  mode {k}: {a:12.4f} Hz (FEBeam.modes)  {b:12.4f} Hz (SciPy eigsh)")
print(f"largest relative difference {worst:.1e}; table: {table}")

# Mode 1 deflected to one thickness at mid-span: its tangent stiffens mode 1.
h = beam.scene.get("Beam/Thickness")
phi = shapes[:, 0]
q = h * phi / np.abs(phi).max()
k_linear = phi @ (beam.stiffness() @ phi)
k_tangent = phi @ (beam.tangent(q) @ phi)
print(f"mode 1 stiffness: linear {k_linear:.6g}, tangent at one thickness {k_tangent:.6g} "
      f"({100 * (k_tangent / k_linear - 1):.1f} % stiffer)")

if worst > 1e-9:
    sys.exit(f"SciPy and FEBeam.modes differ by {worst:.1e}, more than 1e-9")
if not k_tangent > k_linear:
    sys.exit("the deflected beam should be stiffer than the straight one")

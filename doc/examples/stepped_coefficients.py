"""Cubic modal coefficients of a stepped beam read from its Gmsh mesh.

meshes/stepped.prm is a clamped-clamped beam whose thickness steps along its
length (meshes/stepped.msh, physical groups for the sections). The cubic
modal coefficients come from two independent routes: condensed STEP
(enforced modal displacements, the membrane relaxed) and ICE (static
nonlinear solves under modal loads). They must agree; the script prints the
mode-1 self-coefficient b_111 and the largest difference over the tensor.

    PYTHONPATH=build/python python3 doc/examples/stepped_coefficients.py --output out
"""
import argparse
import os
import sys

import numpy as np

import beamslider

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default="stepped_coefficients", help="folder for the coefficient files")
parser.add_argument("--modes", type=int, default=3, help="modes N")
args = parser.parse_args()

scene = beamslider.Scene("stepped")
tensors = {}
for method in ("step-condensed", "ice"):
    result = beamslider.coefficients(scene, method=method, modes=args.modes,
                                     output=os.path.join(args.output, method))
    tensors[method] = result.tensor  # [n, j, k, l], f_n = Σ tensor q_j q_k q_l
    # b_111 = coefficient of q_1³ in f_1.
    print(f"{method:15s} b_111 = {result.tensor[0, 0, 0, 0]:.6e} 1/(s² m² kg)")

step, ice = tensors["step-condensed"], tensors["ice"]
largest = np.abs(step).max()
difference = np.abs(step - ice).max() / largest
print(f"largest |STEP − ICE| over the tensor: {difference:.2e} of its largest entry")
if abs(ice[0, 0, 0, 0] / step[0, 0, 0, 0] - 1) > 1e-3:
    sys.exit("STEP and ICE disagree on b_111 by more than 1e-3")

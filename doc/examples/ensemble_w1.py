"""Two models compared as ensembles, by the Wasserstein distance W₁.

This system is chaotic: two runs of one model that start 1e-9 apart part
ways after a few dozen periods, so models are compared by the distribution
of their outcomes, not trace against trace. Here 20 members of the
published reduced model (5 modes) against 20 of the model with 10 modes (at
half the time step, its explicit step's limit), compared by W₁ of the final
slider positions, computed below from the members and by beamslider itself.
Over the default 12 s the slider has jumped and is on its way back (about
50 s of wall time on two cores); the end state comes by about 25 s
(--end-time 25), where the two models part (report section 5).

    PYTHONPATH=build/python python3 doc/examples/ensemble_w1.py --output out
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import beamslider

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default="ensemble_w1", help="folder for the ensembles and the chart")
parser.add_argument("--members", type=int, default=20)
parser.add_argument("--end-time", type=float, default=12.0, help="simulated time per member [s]")
args = parser.parse_args()

published = beamslider.Scene("mueller2023")
ten_modes = beamslider.Scene("mueller2023")
ten_modes.set("Discretisation/Number of modes", 10)
ten_modes.set("Time stepping/Time step", published.get("Time stepping/Time step") / 2)

# Both ensembles are held in memory; each is saved as the command `ensemble` writes it.
five = beamslider.Ensemble(published, case="signature-move", members=args.members, end_time=args.end_time)
ten = beamslider.Ensemble(ten_modes, case="signature-move", members=args.members, end_time=args.end_time)
five.save(os.path.join(args.output, "rom5"))
ten.save(os.path.join(args.output, "rom10"))

a = np.sort(five.members["final_x_over_L"])
b = np.sort(ten.members["final_x_over_L"])
w1 = np.mean(np.abs(a - b))  # W₁ of two samples of equal size: the mean gap of the sorted values
comparison = ten.compare(five)
row = list(comparison["outcome"]).index("final_x_over_L")
print(f"final x_C/L: 5 modes median {np.median(a):.4f}, 10 modes median {np.median(b):.4f}")
print(f"W1 = {w1:.5f} (beamslider: {comparison['wasserstein'][row]:.5f}, "
      f"90 % interval [{comparison['wasserstein_low'][row]:.5f}, {comparison['wasserstein_high'][row]:.5f}],"
      f" own spread {comparison['own_spread'][row]:.5f})")
if abs(w1 - comparison["wasserstein"][row]) > 1e-12:  # the same numbers, unrounded
    sys.exit(f"W1 from the members ({w1}) differs from beamslider's ({comparison['wasserstein'][row]})")

figure, axes = plt.subplots(figsize=(6, 3))
axes.plot(a, np.zeros_like(a), "o", alpha=0.6, label="ROM, 5 modes (published)")
axes.plot(b, np.ones_like(b), "o", alpha=0.6, label="ROM, 10 modes")
axes.set_yticks([0, 1], ["5 modes", "10 modes"])
axes.set_xlabel(f"final slider position $x_C/L$ after {args.end_time:g} s")
axes.set_title(f"{args.members} members each; W₁ = {w1:.4f}")
figure.tight_layout()
figure.savefig(os.path.join(args.output, "ensemble_w1.png"), dpi=120)


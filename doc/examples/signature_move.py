"""The signature move of the published system, from Python.

Runs the case `signature-move` (124 Hz, 14 m/s², slider from x_C/L = 0.3) on
the published reduced model (5 modes), prints the one-line verdict and draws
the slider's position and the vibration amplitude against time. With
--with-fe the FE beam (32 elements, its own time step) runs too, about two
minutes more: the picture on README's front page.

    PYTHONPATH=build/python python3 doc/examples/signature_move.py --output out
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import beamslider

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default="signature_move", help="folder for the chart and the runs' files")
parser.add_argument("--end-time", type=float, default=20.0, help="simulated time [s]")
parser.add_argument("--with-fe", action="store_true", help="also run the FE beam (about two minutes)")
args = parser.parse_args()
os.makedirs(args.output, exist_ok=True)

scene = beamslider.Scene("mueller2023")
runs = {"ROM, 5 modes (published)": beamslider.simulate(scene, model="rom", case="signature-move",
                                                        end_time=args.end_time,
                                                        output=os.path.join(args.output, "rom"))}
if args.with_fe:
    runs["FE beam, 32 elements"] = beamslider.simulate(scene, model="fe", case="signature-move",
                                                       end_time=args.end_time,
                                                       output=os.path.join(args.output, "fe"),
                                                       progress=lambda line: print("  " + line, flush=True))

figure, (position, amplitude) = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
for label, run in runs.items():
    print(f"{label}: {run.verdict}")
    position.plot(run.trace["t_s"], run.trace["slider_x_over_L"], label=label)
    amplitude.plot(run.trace["t_s"], run.trace["amplitude_over_h"], label=label)
position.set_ylabel("slider position $x_C/L$")
amplitude.set_ylabel("vibration amplitude $w(L/2)/h$")
amplitude.set_xlabel("time [s]")
position.legend()
position.set_title("Signature move: 124 Hz, 14 m/s², slider from 0.3 L")
figure.tight_layout()
chart = os.path.join(args.output, "signature_move.png")
figure.savefig(chart, dpi=120)
print(f"chart: {chart}")

# The published case is a signature move: toward the clamp, a jump, back
# toward the centre. Anything else means the model has changed.
outcomes = {run.outcome for run in runs.values()}
if outcomes != {"signature move"}:
    sys.exit(f"expected every run to be a signature move, got {outcomes}")

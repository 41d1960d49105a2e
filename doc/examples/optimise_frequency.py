"""An optimisation loop on the model held in Python: the excitation
frequency that maximises the late vibration amplitude.

Each evaluation builds a beamslider.Run of the published reduced model at
one excitation frequency (the slider free, starting at 0.3 L), advances it
by --end-time seconds and returns the mean amplitude w(L/2)/h over its last
60 %. A scan over 100–140 Hz finds the region of the maximum, then SciPy's
bounded scalar minimiser refines it. Prints the number of evaluations, the
wall time per evaluation, the best frequency and its amplitude, and writes
the scan as a CSV and a chart.

    PYTHONPATH=build/python python3 doc/examples/optimise_frequency.py --output out
"""
import argparse
import os
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import scipy.optimize

import beamslider

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default="optimise_frequency", help="folder for the scan and the chart")
parser.add_argument("--end-time", type=float, default=0.5, help="simulated time per evaluation [s]")
parser.add_argument("--points", type=int, default=200, help="frequencies in the scan")
args = parser.parse_args()
os.makedirs(args.output, exist_ok=True)

scene = beamslider.Scene("mueller2023")
evaluations = []


def late_amplitude(frequency_hz):
    """Mean amplitude w(L/2)/h over the last 60 % of a run at frequency_hz."""
    scene.set("Excitation/Frequency", float(frequency_hz))
    run = beamslider.Run(scene)
    run.advance(args.end_time)
    trace = run.trace
    late = trace["t_s"] >= 0.4 * args.end_time
    value = float(np.mean(trace["amplitude_over_h"][late]))
    evaluations.append((float(frequency_hz), value))
    return value


start = time.perf_counter()
scan = np.linspace(100.0, 140.0, args.points)
amplitudes = np.array([late_amplitude(f) for f in scan])
best = int(np.argmax(amplitudes))
step = scan[1] - scan[0]
refined = scipy.optimize.minimize_scalar(lambda f: -late_amplitude(f), method="bounded",
                                         bounds=(scan[max(best - 2, 0)], scan[min(best + 2, len(scan) - 1)]),
                                         options={"xatol": 1e-3})
wall = time.perf_counter() - start

table = os.path.join(args.output, "evaluations.csv")
with open(table, "w", encoding="utf-8") as f:
    f.write("frequency_hz,late_amplitude_over_h\n")
    for frequency, value in evaluations:
        f.write(f"{frequency!r},{value!r}\n")

figure, axes = plt.subplots(figsize=(7, 4))
axes.plot(scan, amplitudes, ".-", label=f"scan, {len(scan)} runs of {args.end_time:g} s")
axes.plot([refined.x], [-refined.fun], "r*", markersize=12, label=f"refined: {refined.x:.3f} Hz")
axes.set_xlabel("excitation frequency [Hz]")
axes.set_ylabel("late amplitude $w(L/2)/h$")
axes.legend()
figure.tight_layout()
chart = os.path.join(args.output, "optimise_frequency.png")
figure.savefig(chart, dpi=120)

print(f"{len(evaluations)} evaluations in {wall:.1f} s ({1e3 * wall / len(evaluations):.1f} ms each, "
      f"{args.end_time:g} s simulated per run)")
print(f"scan maximum {amplitudes[best]:.4f} h at {scan[best]:.2f} Hz; refined {-refined.fun:.4f} h at "
      f"{refined.x:.3f} Hz")
print(f"table: {table}, chart: {chart}")
if len(evaluations) < 200:
    raise SystemExit(f"only {len(evaluations)} evaluations, fewer than the 200 this example promises")
if -refined.fun < amplitudes[best] - 1e-12 and abs(refined.x - scan[best]) > step:
    raise SystemExit("the refinement ended below the scan's best point away from it")

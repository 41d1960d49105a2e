"""Which modes does the slider's contact excite? (doc/physics.md, "Which
basis a contact scene needs", the modes chosen by participation.)

Runs the scene's explicit ROM with N modes at Δt/k from the slider at rest,
and samples it every 37 steps (a prime, so the samples do not lock to the
excitation's period). Per mode n it prints

- the energy share: the time average of ½(u_n² + ω_n² q_n²) over the run,
  divided by its sum over the modes (q mass-normalised, so this is energy);
- the impulse share: the mean square of the modal contact impulse
  Σ_k φ_n(x_k) P_k over the sampled steps (P_k the normal impulse at corner
  k, x_k its position), divided by its sum: what each impact feeds mode n;
- each mode's rank by either measure.

A study that prints numbers and asserts nothing (the measurements are in
doc/findings.md). Usage, from the repository's root after the build:

    PYTHONPATH=build/python /usr/bin/python3 scripts/modal_participation.py \
        [--scene mueller2023] [--modes 20] [--step-divisor 4] [--end-time 40]
"""
import argparse
import time

import numpy as np

import beamslider as bs


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="mueller2023")
    parser.add_argument("--modes", type=int, default=20)
    parser.add_argument("--step-divisor", type=int, default=4,
                        help="the run's step is the scene's Time step over this (N = 20 needs 4)")
    parser.add_argument("--end-time", type=float, default=40.0, help="[s]")
    args = parser.parse_args()

    scene = bs.Scene(args.scene)
    dt = float(scene.get("Time stepping/Time step")) / args.step_divisor
    scene.set("Discretisation/Number of modes", args.modes)
    scene.set("Time stepping/Time step", dt)
    scene.set("Time stepping/End time", args.end_time)
    rom = bs.ReducedModel(scene)
    omega = np.asarray(rom.omega)
    half_width = 0.5 * float(scene.get("Slider/Window width"))

    run = bs.Run(scene, "rom")
    every, n_steps, done = 37, int(round(args.end_time / dt)), 0
    energy, impulse, n_samples = np.zeros(args.modes), np.zeros(args.modes), 0
    status, start = "completed", time.time()
    while done < n_steps and status == "completed":
        status = run.step(min(every, n_steps - done))
        done += every
        s = run.state
        q, u = np.asarray(s["q"]), np.asarray(s["u"])
        energy += 0.5 * (u**2 + omega**2 * q**2)
        n_samples += 1
        normal = np.asarray(s["contact_impulses"])[:, 0]  # upper-left, upper-right, lower-left, lower-right
        if normal.any():
            x = s["slider_x"]
            phi, _ = rom.shapes([x - half_width, x + half_width, x - half_width, x + half_width])
            impulse += (np.asarray(phi).T @ normal) ** 2

    energy_share, impulse_share = energy / energy.sum(), impulse / max(impulse.sum(), 1e-300)
    rank = lambda v: np.argsort(np.argsort(-v)) + 1
    print(f"# {args.scene}, N = {args.modes}, Δt = {dt:g} s, {args.end_time:g} s: {status}, "
          f"end x_C/L = {run.state['slider_x_over_L']:.4f}, {n_samples} samples, "
          f"{time.time() - start:.0f} s wall")
    print("mode  f [Hz]  energy_share  impulse_share  rank_energy  rank_impulse")
    for n, (e, p, re, rp) in enumerate(zip(energy_share, impulse_share, rank(energy_share), rank(impulse_share))):
        print(f"{n + 1:4d} {omega[n] / (2 * np.pi):8.1f}  {e:11.3e}  {p:12.3e}  {re:10d}  {rp:11d}")


if __name__ == "__main__":
    main()

"""What the Python objects cost beyond the C++ they call (issue: Python on
the library): `import beamslider`, building a Run, the overhead of one
short advance, and a 1 s ROM run per step against the C++ step benchmark
RomContact/5 (Google Benchmark, same build). A benchmark, not a test: it
prints the numbers and asserts nothing.

    PYTHONPATH=build/python /usr/bin/python3 verification/benchmarks/python_run_overhead.py
"""
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BENCHMARKS = os.path.join(ROOT, "build", "verification", "beamslider_benchmarks")


def best_of(n, f):
    times = []
    for _ in range(n):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def python_seconds(code):
    return best_of(5, lambda: subprocess.run([sys.executable, "-c", code], check=True))


import_seconds = python_seconds("import beamslider") - python_seconds("pass")

import beamslider  # noqa: E402  (after the subprocess measurements)

build_seconds = best_of(5, lambda: beamslider.Run())
# The stepping itself per step, from a long advance (the trace's rows and the
# period bookkeeping included, as in the C++ run).
long_run = beamslider.Run()
steps_long = 500_000
long_seconds = best_of(1, lambda: long_run.step(steps_long))
per_step = long_seconds / steps_long


def short_advance():
    run = beamslider.Run()
    start = time.perf_counter()
    run.advance(0.01)
    return time.perf_counter() - start, round(0.01 / run.time_step)


short = [short_advance() for _ in range(20)]
short_seconds, short_steps = min(short)
overhead = short_seconds - short_steps * per_step


def one_second_run():
    run = beamslider.Run()
    start = time.perf_counter()
    run.advance(1.0)
    return (time.perf_counter() - start) / round(1.0 / run.time_step)


python_per_step = min(one_second_run() for _ in range(5))

cpp_per_step = float("nan")
if os.path.exists(BENCHMARKS):
    done = subprocess.run([BENCHMARKS, "--benchmark_filter=RomContact/5", "--benchmark_format=json"],
                          capture_output=True, text=True, check=True)
    row = json.loads(done.stdout)["benchmarks"][0]
    cpp_per_step = row["us/step"] * 1e-6

print("| what | measured | goal |")
print("|---|---|---|")
print(f"| `import beamslider` (beyond Python's start) | {import_seconds:.2f} s | ≤ 0.5 s |")
print(f"| `Run()` (the published ROM built: FE modes, basis) | {1e3 * build_seconds:.1f} ms | |")
print(f"| `Run.advance(0.01)` beyond its {short_steps} steps | {1e3 * overhead:.3f} ms | ≤ 5 ms |")
print(f"| 1 s ROM run from Python, per step | {1e6 * python_per_step:.3f} µs | |")
print(f"| the first 10 s from Python (as RomContact/5 runs them), per step | {1e6 * per_step:.3f} µs | |")
print(f"| C++ `RomContact/5` (first 10 s of the signature move), per step | {1e6 * cpp_per_step:.3f} µs | |")
print(f"| Python against C++, the same 10 s | {100 * (per_step / cpp_per_step - 1):+.0f} % | ≤ +10 % |")

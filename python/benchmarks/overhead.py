#!/usr/bin/env python3
"""Overhead of the Python module against the same C++ call, on the samples.

    PYTHONPATH=build/python python3 python/benchmarks/overhead.py REC... [--repeats N]

For analyze() and one fit cost evaluation (FitProblem.evaluate), the same library call is timed
inside C++ (oscilab._native._oscilab._bench_*: steady clock, GIL released) and through the
module (time.perf_counter around the Python call), alternately, and the medians and their ratio
are printed. The target is an overhead below 5 %. ctest runs it once (label benchmark); it
asserts nothing about speed.
"""

import argparse
import statistics
import time

import oscilab
from oscilab._native import _oscilab as native


def timed(call, repeats):
    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        seconds.append(time.perf_counter() - start)
    return seconds


def report(name, python_s, cxx_s):
    py, cxx = statistics.median(python_s), statistics.median(cxx_s)
    print(f"BM_python_{name:<10} python {py * 1e3:10.3f} ms   C++ {cxx * 1e3:10.3f} ms   "
          f"ratio {py / cxx:6.3f}   overhead {100 * (py / cxx - 1):+6.2f} %   "
          f"(medians of {len(python_s)})", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recordings", nargs="+")
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()

    native._bench_analyze(args.recordings, 1)  # warm up: FFTW plans, file cache
    python_s, cxx_s = [], []
    for _ in range(args.repeats):
        python_s += timed(lambda: oscilab.analyze(args.recordings), 1)
        cxx_s += native._bench_analyze(args.recordings, 1)
    report("analyze", python_s, cxx_s)

    problem = oscilab.prepare_fit(oscilab.analyze(args.recordings))
    theta = problem.initial_theta
    problem.evaluate(theta)
    python_s, cxx_s = [], []
    for _ in range(args.repeats * 3):
        python_s += timed(lambda: problem.evaluate(theta), 1)
        cxx_s += native._bench_evaluate(problem, theta, 1)
    report("evaluate", python_s, cxx_s)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Detection-power curves of the model-gap diagnosis from diagnosis_power_study.sh's results.

    python3 scripts/diagnosis_power_plot.py OUT/results.csv OUT/detection_power.png

One panel per hidden effect: the share of runs that named it against its strength (× the
reference strength), one line per condition (frequency, sensor noise), and in grey on the right
axis the size of its signature: the reduced χ² the paper's form leaves (the noise level of a
correct model is about 1.6); the controls' false-positive rate in the title. Needs matplotlib
(Debian: python3-matplotlib).
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(results_path: str, png_path: str) -> None:
    rows = list(csv.DictReader(open(results_path)))
    runs = defaultdict(lambda: [0, 0])  # (effect, condition, scale) -> [named, runs]
    signature = defaultdict(list)  # (effect, scale) -> baseline reduced χ² at 9 Hz, noise ×1
    controls = [r for r in rows if r["case"] == "control"]
    for r in rows:
        if r["case"] != "power":
            continue
        condition = f'{float(r["freq_hz"]):g} Hz, noise x{float(r["noise_scale"]):g}'
        key = (r["effect"], condition, float(r["scale"]))
        runs[key][0] += int(r["correct"])
        runs[key][1] += 1
        if condition == "9 Hz, noise x1":
            signature[(r["effect"], float(r["scale"]))].append(float(r["baseline_reduced_chi2"]))
    effects = sorted({k[0] for k in runs})
    columns = 4
    rows_count = (len(effects) + columns - 1) // columns
    fig, axes = plt.subplots(rows_count, columns, figsize=(4 * columns, 3.2 * rows_count),
                             squeeze=False, sharey=True)
    for index, effect in enumerate(effects):
        ax = axes[index // columns][index % columns]
        conditions = sorted({k[1] for k in runs if k[0] == effect})
        markers = ["o", "s", "^", "v", "D"]
        for number, condition in enumerate(conditions):
            points = sorted((k[2], v[0] / v[1], v[1]) for k, v in runs.items()
                            if k[0] == effect and k[1] == condition)
            offset = 0.02 * (number - (len(conditions) - 1) / 2)  # keep coinciding lines apart
            ax.plot([p[0] for p in points], [p[1] + offset for p in points],
                    marker=markers[number % len(markers)], markersize=5,
                    linestyle="-" if condition == "9 Hz, noise x1" else ":", label=condition)
        size = sorted((k[1], sum(v) / len(v)) for k, v in signature.items() if k[0] == effect)
        if size:
            right = ax.twinx()
            right.plot([p[0] for p in size], [p[1] for p in size], color="grey", alpha=0.6,
                       linewidth=3, label="baseline chi2/dof")
            right.axhline(1.6, color="grey", linestyle="--", linewidth=0.8)
            right.set_yscale("log")
            if index % columns == columns - 1 or index == len(effects) - 1:
                right.set_ylabel("paper form's chi2/dof (grey)")
        ax.set_xscale("log")
        ax.set_ylim(-0.05, 1.05)
        ax.set_title(effect, fontsize=10)
        ax.set_xlabel("strength (x reference)")
        ax.grid(True, alpha=0.3)
        if index % columns == 0:
            ax.set_ylabel("named correctly")
        ax.legend(fontsize=7)
    for index in range(len(effects), rows_count * columns):
        axes[index // columns][index % columns].axis("off")
    false_positives = sum(1 for r in controls if r["verdict"] != "none")
    fig.suptitle(f"Detection power of the diagnosis (controls: {false_positives} false positives "
                 f"in {len(controls)})")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: diagnosis_power_plot.py RESULTS.csv OUT.png")
    main(sys.argv[1], sys.argv[2])

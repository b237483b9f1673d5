#!/usr/bin/env python3
"""Compare the generated f64 kernels of two or more `rne` binaries on this noisy host: each
binary's `rne bench --quick` runs in turn, ROUNDS times, so that every binary sees the host's
slow and fast phases alike, and the table gives each kernel's minimum (the fast phase) and
median over the rounds, in ns per call, from the "generated f64" rows of the reports.

    python3 tools/compare/kernels.py 10 before=/tmp/rne-before after=./target-native/release/rne

The reports go to /tmp/compare-TAG. Robots and kernels: ROBOTS and KERNELS below.
"""
import re
import statistics
import subprocess
import sys

ROBOTS = ("puma560", "ur5", "panda-arm")
KERNELS = ("inverse_dynamics", "mass_matrix", "forward_dynamics")


def times(report):
    """{(robot, kernel): ns} of the generated f64 rows of one bench report."""
    found, robot = {}, None
    for line in open(report, encoding="utf-8"):
        heading = re.match(r"### (\S+) \(", line)
        if heading:
            robot = heading.group(1)
        row = re.match(r"\| (\w+) \| generated f64 \| ([\d.]+) \|", line)
        if row and robot in ROBOTS and row.group(1) in KERNELS:
            found[(robot, row.group(1))] = float(row.group(2))
    return found


def main():
    if len(sys.argv) < 3 or not sys.argv[1].isdigit():
        sys.exit(__doc__)
    rounds = int(sys.argv[1])
    binaries = [arg.split("=", 1) for arg in sys.argv[2:]]
    samples = {}
    for _ in range(rounds):
        for tag, binary in binaries:
            out = f"/tmp/compare-{tag}"
            subprocess.run(
                ["nice", "-n", "-19", binary, "bench", "--quick", "--quiet", "--out", out],
                check=True,
                stdout=subprocess.DEVNULL,
            )
            for key, ns in times(f"{out}/bench-report.md").items():
                samples.setdefault(key, {}).setdefault(tag, []).append(ns)
    print("| robot | kernel | " + " | ".join(f"{tag}: min, median" for tag, _ in binaries) + " |")
    print("|---|---|" + "---:|" * len(binaries))
    for (robot, kernel), by_tag in samples.items():
        cells = [
            f"{min(by_tag[tag]):.1f}, {statistics.median(by_tag[tag]):.1f}" for tag, _ in binaries
        ]
        print(f"| {robot} | {kernel} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()

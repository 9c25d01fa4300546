#!/usr/bin/env python3
"""Axis dynamics of a PVT program read back from its NC alone (the Precitech dialect).

usage: nc_pvt_dynamics.py PROGRAM.nc MACHINE.yaml TIME

TIME: the letter of the time word every data line but the first carries (seconds), or
`feed` for a program at one feed (its G01 F word, mm/min: a profile), where a block's time
is its X-Z chord over the feed.

The data lines carry the machine's axes that the first of them holds (C, X, Z on a spiral;
X, Z on a profile). A PVT controller
derives each axis's velocity at a block from its neighbours, (q[k+1] − q[k−1]) / (t[k+1] −
t[k−1]), one-sided at the program's two ends, and runs the cubic Hermite through the
positions and those velocities. Per block: the cubic's largest speed (its velocity is
quadratic in time: at an end or at its vertex) and its accelerations at both ends (linear in
time between them). The first block starts from rest, reaching its start velocity over its
time; after the last the axis stops from its end velocity over the last block's time. C is
unwrapped. Prints each axis's peak velocity and acceleration against the machine YAML's
limits, and where the largest share of a limit is; exits 1 when a limit is exceeded. Shares
no code with freeturn.
"""
import math
import re
import sys


def machine_limits(path):
    limits = {}
    for line in open(path, encoding="utf-8"):
        m = re.match(r"\s*-\s*\{(.*)\}\s*$", line)
        if m and "name:" in m.group(1):
            fields = dict((k.strip(), v.strip()) for k, v in (f.split(":", 1) for f in m.group(1).split(",")))
            limits[fields["name"]] = (float(fields.get("max_velocity", "inf")),
                                      float(fields.get("max_acceleration", "inf")))
    return limits


def main():
    program, machine, letter = sys.argv[1], sys.argv[2], sys.argv[3]
    limits = machine_limits(machine)
    word = re.compile(r"([A-Z])([-+]?[0-9]*\.?[0-9]+)")
    q = None
    times = [0.0]
    feed = None
    for line in open(program, encoding="utf-8"):
        if line.startswith(";"):
            continue
        if line.startswith("G"):
            m = re.search(r"F([0-9.]+)", line)
            if m:
                feed = float(m.group(1)) / 60
            continue
        words = dict(word.findall(line))
        if "X" not in words:
            continue
        if q is None:
            q = {a: [] for a in limits if a in words}
        if not all(a in words for a in q):
            continue
        for a in q:
            q[a].append(float(words[a]))
        if letter == "feed" and len(q["X"]) > 1 and feed:
            times.append(times[-1] + math.hypot(q["X"][-1] - q["X"][-2], q["Z"][-1] - q["Z"][-2]) / feed)
        elif letter in words:
            times.append(times[-1] + float(words[letter]))
    if q is None:
        sys.exit(f"{program}: no data lines")
    limits = {a: limits[a] for a in q}
    n = len(times)
    if n < 2 or any(len(v) != n for v in q.values()):
        sys.exit(f"{program}: expected a time word on every data line but the first, or a feed")
    if "C" in q:
        c = q["C"]
        for k in range(1, n):
            c[k] = c[k - 1] + (c[k] - c[k - 1] + 180.0) % 360.0 - 180.0
    worst_share, worst_where, failed = 0.0, "", False
    for axis, (v_max, a_max) in limits.items():
        x = q[axis]

        def velocity(k):
            lo, hi = max(k - 1, 0), min(k + 1, n - 1)
            return (x[hi] - x[lo]) / (times[hi] - times[lo])

        peak_v = peak_a = 0.0
        where_v = where_a = ""
        for k in range(n - 1):
            h = times[k + 1] - times[k]
            d = x[k + 1] - x[k]
            va, vb = velocity(k), velocity(k + 1)
            # v(u) = A u² + B u + va over the block (u its fraction of the time).
            A = 3 * (va + vb) - 6 * d / h
            B = 6 * d / h - 4 * va - 2 * vb
            speed = max(abs(va), abs(vb))
            if A != 0 and 0 < -B / (2 * A) < 1:
                speed = max(speed, abs(va - B * B / (4 * A)))
            if speed > peak_v:
                peak_v, where_v = speed, f"block {k + 1}"
            for a in ((6 * d - 4 * h * va - 2 * h * vb) / h**2, (-6 * d + 2 * h * va + 4 * h * vb) / h**2):
                if abs(a) > peak_a:
                    peak_a, where_a = abs(a), f"block {k + 1}"
        start = abs(velocity(0)) / (times[1] - times[0])
        stop = abs(velocity(n - 1)) / (times[-1] - times[-2])
        if start > peak_a:
            peak_a, where_a = start, "the start from rest"
        if stop > peak_a:
            peak_a, where_a = stop, "the stop after the last block"
        print(f"{axis}: velocity {peak_v:.6g} of {v_max:g} ({where_v}), "
              f"acceleration {peak_a:.6g} of {a_max:g} ({where_a})")
        for share, where in ((peak_v / v_max, f"{axis} velocity at {where_v}"),
                             (peak_a / a_max, f"{axis} acceleration at {where_a}")):
            if share > worst_share:
                worst_share, worst_where = share, where
            failed |= share > 1 + 1e-9
    print(f"largest share of a limit: {worst_share:.4f} ({worst_where})")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()

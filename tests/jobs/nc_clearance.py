#!/usr/bin/env python3
"""The nose never enters a convex sphere, on any move of a written NC program.

usage: nc_clearance.py PROGRAM.nc SPHERE_RADIUS NOSE_RADIUS

The part is a convex sphere of radius Rs with its vertex at Z = 0 (its centre on the
axis at Z = -Rs); the program points the nose centre (X radius, Z along the axis). C is
ignored: the part is revolved. Follows M98 calls into child files; skips lines that leave
the work frame (G53) and everything before the first Z word. Every straight move, end to
end, must keep the nose centre at least Rs + R - 0.1 um from the sphere's centre: the
closest point of the segment to the centre is found in closed form. Prints the smallest
clearance and exits 1 when a move cuts into the part. Shares no code with freeturn.
"""
import math
import os
import re
import sys

WORD = re.compile(r"([A-Z])([-+]?(?:\d+\.?\d*|\.\d+))")


def lines_of(path):
    folder = os.path.dirname(path)
    for line in open(path, encoding="ascii"):
        call = re.match(r"\s*M98\s*\(?([^)\s]+)\)?", line)
        if call:
            yield from lines_of(os.path.join(folder, call.group(1)))
            continue
        line = re.sub(r"\([^)]*\)|;.*", "", line).strip()
        if line:
            yield line


def closest_distance(a, b, centre):
    """Smallest distance from `centre` to the segment a-b (2D)."""
    ax, az = a[0] - centre[0], a[1] - centre[1]
    dx, dz = b[0] - a[0], b[1] - a[1]
    length2 = dx * dx + dz * dz
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, -(ax * dx + az * dz) / length2))
    return math.hypot(ax + t * dx, az + t * dz)


def main():
    program, sphere, nose = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    centre = (0.0, -sphere)
    need = sphere + nose - 1e-4
    x = z = None
    worst, worst_line, moves = math.inf, "", 0
    for line in lines_of(program):
        words = {k: float(v) for k, v in WORD.findall(line)}
        if any(k == "G" and float(v) == 53 for k, v in WORD.findall(line)):
            continue
        nx, nz = words.get("X", x), words.get("Z", z)
        if nz is None or nx is None:
            x, z = nx, nz
            continue
        if x is not None and z is not None and (nx, nz) != (x, z):
            moves += 1
            d = closest_distance((x, z), (nx, nz), centre)
            if d < worst:
                worst, worst_line = d, line
        x, z = nx, nz
    print(f"{moves} moves; smallest clearance {(worst - sphere - nose) * 1e6:.1f} nm at '{worst_line}'")
    return 0 if worst >= need and moves > 0 else 1


if __name__ == "__main__":
    sys.exit(main())

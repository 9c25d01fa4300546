#!/usr/bin/env python3
"""The deepest the cutting edge goes below a rotationally symmetric design, read from a
Precitech X-Z program alone (profile mode, PVT).

The controller moves X and Z along cubic Hermites through the blocks, each block's time its
X-Z chord over the feed, the velocity at a block the central difference of its neighbours
(one-sided at the ends). The edge is an arc of radius R in the rake plane, h above the
spindle line: its point at angle phi, from the nose centre (x, z), sits at
(x - R sin phi, h, z - R cos phi), so the part turning under it is cut at radius
sqrt((x - R sin phi)^2 + h^2). The blocks are sampled 256 times each, the arc every 0.05
degrees; the designs are written here from their definitions (docs/surfaces.md), sharing
no code with freeturn. X is written negated (the Precitech's sign).

usage: nc_profile_gouge.py PROGRAM.nc DESIGN R H HALF_ANGLE_DEG R_MAX
DESIGN: sinusoidal_ring:AMPLITUDE:PERIOD (A sin(2 pi r / period)) or sphere:RADIUS
Prints the deepest point (nm, > 0 below the design).
"""
import re
import sys

import numpy as np


def main():
    path, design = sys.argv[1:3]
    R, h, half, r_max = map(float, sys.argv[3:7])
    kind, *p = design.split(":")
    if kind == "sphere":
        c = 1 / float(p[0])
        z_of = lambda r: c * r * r / (1 + np.sqrt(1 - c * c * r * r))
    else:
        amplitude, omega = float(p[0]), 2 * np.pi / float(p[1])
        z_of = lambda r: amplitude * np.sin(omega * r)
    feed, points = None, []
    for line in open(path):
        text = line.split(";")[0].strip()
        m = re.search(r"F([-\d.]+)", text)
        if m:
            feed = float(m.group(1))
        m = re.match(r"X([-\d.]+)Z([-\d.]+)$", text)
        if m:
            points.append((-float(m.group(1)), float(m.group(2))))
    p = np.array(points)
    dt = np.hypot(*np.diff(p, axis=0).T) / (feed / 60)
    t = np.concatenate([[0], np.cumsum(dt)])
    v = np.zeros_like(p)
    v[1:-1] = (p[2:] - p[:-2]) / (t[2:] - t[:-2])[:, None]
    v[0], v[-1] = (p[1] - p[0]) / dt[0], (p[-1] - p[-2]) / dt[-1]
    u = np.linspace(0, 1, 257)[:, None]
    h00, h10, h01, h11 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u, -2 * u**3 + 3 * u**2, u**3 - u**2
    phi = np.radians(np.arange(-half, half + 1e-9, 0.05))
    deepest = -1.0
    for k in range(len(p) - 1):
        q = h00 * p[k] + h10 * dt[k] * v[k] + h01 * p[k + 1] + h11 * dt[k] * v[k + 1]
        xe, ze = q[:, :1] - R * np.sin(phi), q[:, 1:] - R * np.cos(phi)
        r = np.sqrt(xe**2 + h * h)
        below = np.where(r <= r_max, z_of(r) - ze, -1.0)
        deepest = max(deepest, float(below.max()))
    print("%.3f" % (deepest * 1e6))


if __name__ == "__main__":
    main()

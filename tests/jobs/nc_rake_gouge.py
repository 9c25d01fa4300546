#!/usr/bin/env python3
"""The deepest the cutting edge goes below a design, read from a Moore program alone.

The edge is an arc of radius R in the rake plane, machine y = h (the tool's centre height):
its point at angle phi sits at machine (X - R sin phi, h, Z - R cos phi), the part turned
by C. The blocks' X, Z and C are interpolated linearly (2 samples a block), or, in a PVT
program (a T word on every block), along the controller's cubics in time (16 samples a
block); the arc every 0.25 degrees; the designs are written here from their definitions
(docs/surfaces.md), sharing no code with freeturn.

usage: nc_rake_gouge.py PROGRAM.nc DESIGN R H HALF_ANGLE_DEG R_MIN R_MAX [WAVINESS]
DESIGN: decentred_sphere:RADIUS:DX, compound_eye:BASE:LENS:DIAMETER:PITCH:EXTENT (rings),
        microlens_array:LENS:DIAMETER:PITCH:EXTENT[:hexagonal] (square unless hexagonal),
        sinusoidal_ring:AMPLITUDE:PERIOD, sinusoidal_grid:AMPLITUDE:LX:LY, or
        xy_polynomial:NORMALIZATION:I=A,I=A,... (no base conic; term I as in docs/surfaces.md)
WAVINESS: the edge's radius error, DEG:MM,DEG:MM,... (linear between, the ends held): the
edge's point at phi lies R + delta(phi) from the centre.
Prints the deepest point (nm, > 0 below the design).
"""
import os
import re
import sys

import numpy as np

WORD = re.compile(r"([A-Z])\s*([-+]?\d*\.?\d*)")


def read(path, blocks, state):
    folder = os.path.dirname(path)
    for line in open(path):
        call = re.search(r"M98\s*\(([^)]+)\)", line)
        if call:
            read(os.path.join(folder, call.group(1)), blocks, state)
            continue
        text = re.sub(r"\(.*?\)", "", line.split(";")[0]).strip()
        if not text or "G53" in text:  # machine coordinates: the home move
            continue
        words = {k: float(v) for k, v in WORD.findall(text) if v not in ("", ".", "-", "+")}
        if any(a in words for a in "XZC"):
            state.update({a: words[a] for a in "XZC" if a in words})
            if state["X"] is not None and state["Z"] is not None:
                blocks.append((state["X"], state["Z"], state["C"], words.get("T", np.nan)))
        if words.get("M") in (2.0, 30.0):
            break
    return blocks


def sphere_sag(c, r2):
    return c * r2 / (1 + np.sqrt(np.maximum(1 - c * c * r2, 0.0)))  # a hemisphere's rim rounds past 1


def decentred_sphere(radius, dx):
    c = 1 / radius
    return lambda x, y: sphere_sag(c, (x + dx) ** 2 + y * y) - sphere_sag(c, dx * dx)


def compound_eye(base, lens, diameter, pitch, extent):
    cb = 1 / base
    vertex = sphere_sag(cb, (diameter / 2) ** 2) - sphere_sag(1 / lens, (diameter / 2) ** 2)
    centres, k = [], 0
    while True:
        rho = base * np.sin(k * pitch / base)
        if rho > extent - diameter / 2 + 1e-12:
            break
        count = 1 if k == 0 else int(np.floor(2 * np.pi * rho / pitch))
        for j in range(count):
            x, y = rho * np.cos(2 * np.pi * j / count), rho * np.sin(2 * np.pi * j / count)
            q = np.sqrt(1 - cb * cb * (x * x + y * y))
            n = np.array([-cb * x / q, -cb * y / q, 1.0])
            n /= np.linalg.norm(n)  # the base's normal, along which the lenslet's axis lies
            top = np.array([x, y, sphere_sag(cb, x * x + y * y)]) + vertex * n
            centres.append(top + lens * n)
        k += 1

    def z(x, y):
        out = sphere_sag(cb, x * x + y * y)
        for c in centres:
            near = (x - c[0]) ** 2 + (y - c[1]) ** 2 < (diameter / 2 + 0.05) ** 2
            if near.any():
                s = lens * lens - (x[near] - c[0]) ** 2 - (y[near] - c[1]) ** 2
                lenslet = c[2] - np.sign(lens) * np.sqrt(np.maximum(s, 0))
                if lens > 0:  # a bowl: below the base inside its rim, above it outside
                    out[near] = np.minimum(out[near], np.where(s > 0, lenslet, np.inf))
                else:  # a dome: above the base inside its rim
                    out[near] = np.maximum(out[near], lenslet)
        return out

    return z


def microlens_array(lens, diameter, pitch, extent, lattice="square"):
    """Spherical lenslets on the plane z = 0 (docs/surfaces.md): a square lattice, or a
    hexagonal one, rows pitch*sqrt(3)/2 apart, every odd row moved half a pitch along x."""
    c = 1 / lens
    rim = sphere_sag(c, (diameter / 2) ** 2)
    hexagonal = lattice == "hexagonal"
    dy = pitch * np.sqrt(3.0) / 2 if hexagonal else pitch
    n = int(np.ceil(extent / dy)) + 1
    grid = [((i + (0.5 if hexagonal and j % 2 != 0 else 0.0)) * pitch, j * dy)
            for i in range(-n, n + 1) for j in range(-n, n + 1)]
    centres = [(x, y) for x, y in grid if np.hypot(x, y) <= extent - diameter / 2 + 1e-12]

    def z(x, y):
        out = np.zeros(np.broadcast(x, y).shape)
        for cx, cy in centres:
            d2 = (x - cx) ** 2 + (y - cy) ** 2
            near = d2 < (diameter / 2) ** 2
            if near.any():
                out[near] = sphere_sag(c, d2[near]) - rim
        return out

    return z


def sinusoidal_ring(amplitude, period):
    """z = A sin(2 pi r / period), r the distance from the axis (docs/surfaces.md)."""
    return lambda x, y: amplitude * np.sin(2 * np.pi / period * np.hypot(x, y))


def sinusoidal_grid(amplitude, wavelength_x, wavelength_y):
    """z = A sin(2 pi x / lx) sin(2 pi y / ly) (docs/surfaces.md)."""
    return lambda x, y: amplitude * np.sin(2 * np.pi * x / wavelength_x) * np.sin(2 * np.pi * y / wavelength_y)


def xy_polynomial(normalization, terms):
    """z = sum A_i x^a y^b / Rn^(a+b), i = (n - 1)(n + 2)/2 + b + 1 with n = a + b
    (docs/surfaces.md), no base conic."""
    powers = {}
    for n in range(1, 21):
        for b in range(n + 1):
            powers[(n - 1) * (n + 2) // 2 + b + 1] = (n - b, b)
    pairs = [(powers[int(i)], float(a)) for i, a in (t.split("=") for t in terms.split(","))]
    return lambda x, y: sum(a * (x / normalization) ** px * (y / normalization) ** py
                            for (px, py), a in pairs)


def main():
    path, design, R, h, half, r_min, r_max = sys.argv[1:8]
    R, h, half, r_min, r_max = map(float, (R, h, half, r_min, r_max))
    kind, *p = design.split(":")
    designs = {"decentred_sphere": decentred_sphere, "compound_eye": compound_eye,
               "microlens_array": microlens_array, "sinusoidal_ring": sinusoidal_ring,
               "sinusoidal_grid": sinusoidal_grid}
    if kind == "xy_polynomial":
        z_of = xy_polynomial(float(p[0]), p[1])
    else:
        numbers = [float(v) for v in p if v not in ("square", "hexagonal")]
        z_of = designs[kind](*numbers, *[v for v in p if v in ("square", "hexagonal")])
    b = np.array(read(path, [], {"X": None, "Z": None, "C": 0.0}))
    X, Z, C = b[:, 0], b[:, 1], np.unwrap(np.radians(b[:, 2]))
    if len(b) > 2 and not np.isnan(b[1:, 3]).any():
        # A PVT program (a T word, the block's time, on every block after the first): each
        # axis moves along the cubic Hermite through the blocks in time, each block's
        # velocity the central difference of its neighbours (one-sided at the ends), as the
        # controller interpolates them (tests/jobs/nc_profile_gouge.py), 16 samples a block.
        time = np.concatenate([[0.0], np.cumsum(b[1:, 3])])
        s = np.arange(16) / 16.0
        basis = [2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2]
        dt = np.diff(time)[:, None]

        def cubic(q):
            lo, hi = np.maximum(np.arange(len(q)) - 1, 0), np.minimum(np.arange(len(q)) + 1, len(q) - 1)
            v = (q[hi] - q[lo]) / (time[hi] - time[lo])
            return (basis[0] * q[:-1, None] + basis[1] * dt * v[:-1, None] + basis[2] * q[1:, None] +
                    basis[3] * dt * v[1:, None]).ravel()

        xs, zs, cs = cubic(X), cubic(Z), cubic(C)
    else:
        t = np.array([0.0, 0.5])
        xs = (X[:-1, None] + np.diff(X)[:, None] * t).ravel()
        zs = (Z[:-1, None] + np.diff(Z)[:, None] * t).ravel()
        cs = (C[:-1, None] + np.diff(C)[:, None] * t).ravel()
    phi_deg = np.arange(-half, half + 1e-9, 0.25)
    phi = np.radians(phi_deg)
    radius = np.full(phi.shape, R)
    if len(sys.argv) > 8:
        table = np.array([[float(v) for v in pair.split(":")] for pair in sys.argv[8].split(",")])
        radius = R + np.interp(phi_deg, table[:, 0], table[:, 1])
    deepest = -1.0
    for i in range(0, len(xs), 20000):
        x, z, c = xs[i:i + 20000, None], zs[i:i + 20000, None], cs[i:i + 20000, None]
        ex, ez = x - radius * np.sin(phi), z - radius * np.cos(phi)
        wx, wy = ex * np.cos(c) - h * np.sin(c), ex * np.sin(c) + h * np.cos(c)
        r = np.hypot(wx, wy)
        below = np.where((r >= r_min) & (r <= r_max), z_of(wx, wy) - ez, -1.0)
        deepest = max(deepest, float(below.max()))
    print("%.3f" % (deepest * 1e6))


if __name__ == "__main__":
    main()

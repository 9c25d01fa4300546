#!/usr/bin/env python3
"""The nose's closest approach to a rational B-spline design, read from a Moore program alone.

usage: nc_nurbs_gouge.py PROGRAM.nc NET.json R HALF_ANGLE_DEG [C_SIGN [STRIDE]]

NET.json: {"degree_u", "degree_v", "knots_u", "knots_v", "points" (u-major [x, y, z]),
"weights"}: the job's `nurbs` surface. The design is the height field z(x, y) of
S(u, v) = sum N_i(u) N_j(v) w_ij P_ij / sum N_i(u) N_j(v) w_ij, its basis by the Cox-de Boor
recursion written here (The NURBS Book, eq. 2.5), (u, v) found from (x, y) by Newton's
method on S's first two coordinates with S_u, S_v from the basis' derivatives (eq. 2.9) and
the quotient rule. Shares no code with freeturn.

The blocks' X, Z and C are interpolated linearly (4 samples a block); the nose is the arc
of radius R about (X, Z) within HALF_ANGLE_DEG of straight down, every 1.5 degrees and
about the three highest points of each sample every 1/16 of that, in the radial plane at angle C_SIGN * C (default 1: the part's angle of the spindle's C). With a
STRIDE, only every STRIDE-th block is read (a quicker look). Only
Prints the deepest point of the nose below the design over the whole motion, approach and
retract included (nm; > 0 is a gouge, < 0 is the closest approach above the design).
"""
import json
import math
import os
import re
import sys

import numpy as np

WORD = re.compile(r"([A-Z])([-+]?\d*\.?\d*)")


def basis_and_slope(t, knots, p):
    """N_{i,p}(t) and dN_{i,p}/dt for every i: arrays (len(t), n)."""
    k = np.asarray(knots, float)
    n = len(k) - p - 1
    # The last span is closed on the right, so that t = k[-1] has a basis.
    t = np.clip(t, k[p], k[n])
    last = np.searchsorted(k, k[n], side="left") - 1
    m = len(k) - 1
    N = np.zeros((len(t), m))
    for i in range(m):
        if k[i] < k[i + 1]:
            inside = (t >= k[i]) & ((t < k[i + 1]) | ((i == last) & (t == k[i + 1])))
            N[:, i] = inside
    lower = N
    for d in range(1, p + 1):
        nxt = np.zeros((len(t), m - d))
        for i in range(m - d):
            a = (t - k[i]) / (k[i + d] - k[i]) if k[i + d] > k[i] else 0.0 * t
            b = (k[i + d + 1] - t) / (k[i + d + 1] - k[i + 1]) if k[i + d + 1] > k[i + 1] else 0.0 * t
            nxt[:, i] = a * N[:, i] + b * N[:, i + 1]
        lower, N = N, nxt
    # dN_{i,p} = p (N_{i,p-1}/(k[i+p] - k[i]) - N_{i+1,p-1}/(k[i+p+1] - k[i+1])).
    slope = np.zeros_like(N)
    for i in range(n):
        if k[i + p] > k[i]:
            slope[:, i] += p * lower[:, i] / (k[i + p] - k[i])
        if k[i + p + 1] > k[i + 1]:
            slope[:, i] -= p * lower[:, i + 1] / (k[i + p + 1] - k[i + 1])
    return N, slope


class Design:
    def __init__(self, net):
        self.pu, self.pv = net["degree_u"], net["degree_v"]
        self.ku, self.kv = net["knots_u"], net["knots_v"]
        nu = len(self.ku) - self.pu - 1
        nv = len(self.kv) - self.pv - 1
        P = np.array(net["points"], float).reshape(nu, nv, 3)
        W = np.array(net.get("weights") or [1.0] * (nu * nv), float).reshape(nu, nv)
        self.H = np.concatenate([P * W[:, :, None], W[:, :, None]], axis=2)  # homogeneous
        self.x_range = (P[:, :, 0].min(), P[:, :, 0].max())
        self.y_range = (P[:, :, 1].min(), P[:, :, 1].max())
        self.u_range = (self.ku[self.pu], self.ku[nu])
        self.v_range = (self.kv[self.pv], self.kv[nv])

    def point_and_partials(self, u, v):
        Nu, Du = basis_and_slope(u, self.ku, self.pu)
        Nv, Dv = basis_and_slope(v, self.kv, self.pv)
        rows = np.einsum("ai,ijk->ajk", Nu, self.H, optimize=True)
        rows_u = np.einsum("ai,ijk->ajk", Du, self.H, optimize=True)
        A = np.einsum("aj,ajk->ak", Nv, rows)
        A_u = np.einsum("aj,ajk->ak", Nv, rows_u)
        A_v = np.einsum("aj,ajk->ak", Dv, rows)
        w = A[:, 3:4]
        S = A[:, :3] / w
        S_u = (A_u[:, :3] - S * A_u[:, 3:4]) / w
        S_v = (A_v[:, :3] - S * A_v[:, 3:4]) / w
        return S, S_u, S_v

    def height(self, x, y):
        (u0, u1), (v0, v1) = self.u_range, self.v_range
        (x0, x1), (y0, y1) = self.x_range, self.y_range
        u = u0 + (u1 - u0) * np.clip((x - x0) / (x1 - x0), 0, 1)
        v = v0 + (v1 - v0) * np.clip((y - y0) / (y1 - y0), 0, 1)
        for _ in range(50):
            S, S_u, S_v = self.point_and_partials(u, v)
            rx, ry = S[:, 0] - x, S[:, 1] - y
            if max(np.abs(rx).max(), np.abs(ry).max()) < 1e-12:
                break
            det = S_u[:, 0] * S_v[:, 1] - S_u[:, 1] * S_v[:, 0]
            du = (S_v[:, 1] * rx - S_v[:, 0] * ry) / det
            dv = (-S_u[:, 1] * rx + S_u[:, 0] * ry) / det
            # Damped where a full step would leave the parameter square.
            u = np.clip(u - du, u0, u1)
            v = np.clip(v - dv, v0, v1)
        S, _, _ = self.point_and_partials(u, v)
        miss = max(np.abs(S[:, 0] - x).max(), np.abs(S[:, 1] - y).max())
        if miss > 1e-9:
            sys.exit(f"nc_nurbs_gouge: (x, y) not found on the design to 1e-9 mm (missed by {miss:g})")
        return S[:, 2]


def blocks(path):
    out, state = [], {}

    def read(name):
        for line in open(name, encoding="ascii"):
            call = re.search(r"M98\s*\(([^)]+)\)", line)
            if call:
                read(os.path.join(os.path.dirname(name), call.group(1)))
                continue
            words = dict(WORD.findall(re.sub(r"\([^)]*\)", "", line)))
            if words.get("G") in ("53", "92", "09", "9"):
                continue  # machine coordinates and presets: not the cut's positions
            for k in "XZC":
                if words.get(k):
                    state[k] = float(words[k])
            if all(k in state for k in "XZC"):
                out.append((state["X"], state["Z"], state["C"]))

    read(path)
    return np.array(out)


def main():
    if len(sys.argv) not in (5, 6, 7):
        sys.exit(__doc__)
    program, net_file, R, half = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
    sign = float(sys.argv[5]) if len(sys.argv) >= 6 else 1.0
    stride = int(sys.argv[6]) if len(sys.argv) == 7 else 1
    design = Design(json.load(open(net_file, encoding="utf-8")))
    b = blocks(program)
    cut = b
    phis = np.radians(np.arange(-half, half + 1e-9, 1.5))
    ts = np.array([0.0, 0.25, 0.5, 0.75])
    p0, p1 = cut[:-1:stride], cut[1::stride]
    turn = (p1[:, 2] - p0[:, 2] + 180.0) % 360.0 - 180.0
    X = (p0[:, 0, None] + ts * (p1[:, 0] - p0[:, 0])[:, None]).ravel()
    Z = (p0[:, 1, None] + ts * (p1[:, 1] - p0[:, 1])[:, None]).ravel()
    C = np.radians(sign * (p0[:, 2, None] + ts * turn[:, None]).ravel())
    deepest = -math.inf
    batch = 4000
    for s in range(0, len(X), batch):
        x, z_c, c = X[s : s + batch, None], Z[s : s + batch, None], C[s : s + batch, None]

        def below(phi):  # the design's height over each arc point less the point's (rows, len)
            rho, z = x - R * np.sin(phi), z_c - R * np.cos(phi)
            return design.height((rho * np.cos(c)).ravel(), (rho * np.sin(c)).ravel()).reshape(rho.shape) - z

        coarse = below(phis[None, :])
        # A grid of 1.5 degrees misses a touch by up to R (1 - cos 0.75 degrees), 43 nm on a
        # 0.5 mm nose: each row's three highest arc points are searched again 1/16 as finely.
        fine = np.radians(np.linspace(-0.75, 0.75, 25))
        for k in np.argsort(coarse, axis=1)[:, -3:].T:
            deepest = max(deepest, below(phis[k][:, None] + fine[None, :]).max())
        deepest = max(deepest, coarse.max())
    print(f"{deepest * 1e6:.3f}")


if __name__ == "__main__":
    main()

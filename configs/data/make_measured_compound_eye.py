#!/usr/bin/env python3
"""Writes compound_eye_measured.xyz: the demo's compound eye as a Zygo XYZ export would show
a part cut with a form error, for the compensation example (configs/jobs/compound_eye_compensated.yaml).

The part: the design plus astigmatism (Z6) 0.25 µm and trefoil (Z9) 0.15 µm over R_n = 4 mm.
The instrument: 0.05 mm pixels counted from a corner, the part's axis at pixel (81, 81) and
decentred by (12, -8) µm from it, tilted 5e-5 rad about x and clocked 0.3°; 1 nm noise; a
pixel of every twenty lost (No Data). Heights in µm, as the export writes them.

usage: PYTHONPATH=<build>/python python3 make_measured_compound_eye.py > compound_eye_measured.xyz
"""
import math
import random
import sys

import numpy as np
import freeturn

eye = freeturn.surface("{type: compound_eye, base_radius: 20.0, lens_radius: -5.0, "
                       "lens_diameter: 0.9, pitch: 1.0, pattern: rings}", 4.0)


def zernike_error(x, y):
    rho, phi = np.hypot(x, y) / 4.0, np.arctan2(y, x)
    z6 = math.sqrt(6) * rho**2 * np.cos(2 * phi)  # Noll 6
    z9 = math.sqrt(8) * rho**3 * np.sin(3 * phi)  # Noll 9
    return 0.25e-3 * z6 + 0.15e-3 * z9


# Design frame q = R p + t for an instrument point p (relative to the axis pixel).
tilt_x, clocking, dx, dy = 5e-5, math.radians(0.3), 0.012, -0.008
c, s = math.cos(clocking), math.sin(clocking)
ct, st = math.cos(tilt_x), math.sin(tilt_x)
R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ np.array([[1, 0, 0], [0, ct, -st], [0, st, ct]])
t = np.array([dx, dy, 0.0])
pixel, centre, size = 0.05, 81, 163
random.seed(3)
rows = []
for j in range(size):
    for i in range(size):
        px, py = (i - centre) * pixel, (j - centre) * pixel
        if math.hypot(px, py) > 3.95 or random.random() < 0.05:
            rows.append(f"{i} {j} No Data")
            continue
        z = 0.0  # the height whose design point lies on the part: a fixed point in z
        for _ in range(4):
            q = R @ np.array([px, py, z]) + t
            part = float(eye.sag(q[0], q[1])) + float(zernike_error(q[0], q[1]))
            z += part - q[2]
        rows.append(f"{i} {j} {(z + random.gauss(0, 1e-6)) * 1e3:.7f}")
out = sys.stdout
out.write("Zygo XYZ Data File - Format 1\n1 9 2 0 \"freeturn example\"\n0 0 0 0 0 0\n")
out.write(f"0 0 {size} {size}\n\"compound eye, first part\"\n\"\"\n\"\"\n")
out.write(f"0 0.5 6.328e-07 0 1 1 {pixel * 1e-3:g} 0\n640 480 0 0 0 0 \"\"\n")
out.write("0 0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0 0\n0 \"\"\n1 0\n\"\"\n#\n")
out.write("\n".join(rows) + "\n#\n")

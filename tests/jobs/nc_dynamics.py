#!/usr/bin/env python3
"""Axis dynamics read back from a written NC program alone.

usage: nc_dynamics.py PROGRAM.nc MACHINE.yaml {moore|iso} [--cycle SECONDS]

Follows M98 calls into child files beside the program, takes every inverse-time (G93)
block: its time from F (Moore: seconds; ISO/LinuxCNC: F = 1/minutes) and its axis words.
A feed move per minute (G1 outside G93, F in mm/min) moves each linear axis at its share
of F along the move, a rotary axis alone at F in degrees a minute, a rotary axis beside
linear ones at its turn over their move's time (infinite where a start is not written):
velocity only (the controller ramps such moves itself).
Over each block an axis moves at v = Δ/t (C unwrapped); between two blocks it accelerates
by |Δv| / min(t1, t2); the first block starts from rest and the last ends at rest. Prints
each axis's peak velocity and acceleration against the machine YAML's limits and the sum
of the block times. Exits 1 when a limit is exceeded or the sum differs from --cycle by
more than half a microsecond per block. Shares no code with freeturn.
"""
import math
import os
import re
import sys


def machine_limits(path):
    limits = {}
    rate = math.inf
    for line in open(path, encoding="utf-8"):
        m = re.match(r"\s*-\s*\{(.*)\}\s*$", line)
        if m and "name:" in m.group(1):
            fields = dict(
                (k.strip(), v.strip()) for k, v in (f.split(":", 1) for f in m.group(1).split(","))
            )
            limits[fields["name"]] = (
                float(fields.get("max_velocity", "inf")),
                float(fields.get("max_acceleration", "inf")),
            )
        m = re.match(r"max_block_rate:\s*([0-9.eE+-]+)", line)
        if m:
            rate = float(m.group(1))
    return limits, rate


def lines_of(path):
    folder = os.path.dirname(path)
    for line in open(path, encoding="ascii"):
        line = line.strip()
        call = re.match(r"M98\s*\(?([^)\s]+)\)?", line)
        if call:
            yield from lines_of(os.path.join(folder, call.group(1)))
        else:
            yield line


WORD = re.compile(r"([A-Z])([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)")


def main():
    args = sys.argv[1:]
    cycle = None
    if "--cycle" in args:
        i = args.index("--cycle")
        cycle = float(args[i + 1])
        del args[i : i + 2]
    program, machine, dialect = args
    limits, max_rate = machine_limits(machine)
    position = {}
    inverse_time = False
    block_time = None
    velocity = {a: 0.0 for a in limits}
    last_time = None
    peak_v = {a: 0.0 for a in limits}
    peak_a = {a: 0.0 for a in limits}
    peak_rate = 0.0
    total = 0.0
    blocks = 0
    rapid = False
    feed = None  # the modal F
    for line in lines_of(program):
        if line.startswith("(") or line.startswith(";") or not line:
            continue
        words = WORD.findall(line)
        for letter, value in words:
            if letter == "G" and float(value) in (0, 1):
                rapid = float(value) == 0
            if letter == "F":
                feed = float(value)
            if letter == "G" and float(value) == 93:
                inverse_time = True
            elif letter == "G" and float(value) in (94, 0):
                # Leaving inverse time: the cut ends here, at rest.
                if inverse_time and last_time:
                    for a in limits:
                        peak_a[a] = max(peak_a[a], abs(velocity[a]) / last_time)
                        velocity[a] = 0.0
                    last_time = None
                inverse_time = False
            elif letter == "F" and inverse_time:
                block_time = float(value) if dialect == "moore" else 60.0 / float(value)
        moves = {l: float(v) for l, v in words if l in limits}
        if not moves:
            continue
        if any(l == "G" and float(v) == 53 for l, v in words):
            continue  # machine coordinates: not the work frame's positions
        if not inverse_time and not rapid and feed:
            # A feed per minute: the speed along the linear axes' move (a rotary axis
            # alone: along its own); each axis at its share of it.
            delta = {a: moves[a] - position[a] for a in moves if a in position}
            linear = [a for a in delta if a not in ("B", "C")]
            length = math.sqrt(sum(delta[a] ** 2 for a in linear))
            for a in linear if length > 0 else delta:
                share = abs(delta[a]) / length if length > 0 else 1.0
                peak_v[a] = max(peak_v[a], feed / 60 * share)
            # A rotary axis turning beside linear ones takes their move's time: its turn
            # over that time, infinite where a linear axis' start was never written.
            moved_linear = [a for a in moves if a not in ("B", "C")]
            if length > 0 or any(a not in position for a in moved_linear):
                for a in ("B", "C"):
                    if a not in moves or (a in position and moves[a] == position[a]):
                        continue
                    known = a in position and all(l in position for l in moved_linear)
                    turn = abs(moves[a] - position[a]) if known else math.inf
                    peak_v[a] = max(peak_v[a], turn * feed / 60 / length if known else math.inf)
        if inverse_time and block_time:
            t = block_time
            total += t
            blocks += 1
            peak_rate = max(peak_rate, 1 / t)
            shorter = t if last_time is None else min(t, last_time)
            for a in limits:
                before = position.get(a)
                after = moves.get(a, before)
                delta = 0.0 if before is None or after is None else after - before
                if a == "C":
                    delta = math.remainder(delta, 360.0)
                v = delta / t
                peak_v[a] = max(peak_v[a], abs(v))
                peak_a[a] = max(peak_a[a], abs(v - velocity[a]) / shorter)
                velocity[a] = v
            last_time = t
        position.update(moves)
    if last_time:
        for a in limits:
            peak_a[a] = max(peak_a[a], abs(velocity[a]) / last_time)
    ok = blocks > 0
    for a, (vmax, amax) in sorted(limits.items()):
        print(f"{a}: velocity {peak_v[a]:.6g} of {vmax:g}, acceleration {peak_a[a]:.6g} of {amax:g}")
        ok = ok and peak_v[a] <= vmax and peak_a[a] <= amax
    print(f"block rate {peak_rate:.6g} of {max_rate:g}; {blocks} timed blocks, {total:.6f} s")
    ok = ok and peak_rate <= max_rate * (1 + 1e-9)
    if cycle is not None:
        print(f"report's cycle time {cycle:.6f} s")
        ok = ok and abs(total - cycle) <= 0.5e-6 * blocks + 1e-9
    print("within the limits" if ok else "EXCEEDS the limits or the cycle time")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())

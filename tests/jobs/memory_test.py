#!/usr/bin/env python3
"""check, and a run with nc: false, hold bounded memory: flat in the path's length.

The off-axis parabola job at two pitches, the second with eight times the points (30 000
and 240 000); each is run as a child process and its peak resident set (ru_maxrss) read
back. The longer path may not cost more than 1 MB beyond the shorter: a record kept per
point (an axis record is 40 bytes) would be 8 MB or more, and so would a planner band
whose length grew with the path's. usage: memory_test.py FREETURN SOURCE_DIR
"""
import os
import resource
import subprocess
import sys
import tempfile


def peak_kb(command):
    # A fresh Python per run: ru_maxrss of RUSAGE_CHILDREN is the largest over all children.
    probe = ("import resource, subprocess, sys\n"
             "r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL)\n"
             "print(r.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    out = subprocess.run([sys.executable, "-c", probe] + command, capture_output=True, text=True, check=True)
    code, kb = out.stdout.split()
    if code != "0":
        sys.exit(f"FAIL: {' '.join(command)} exited {code}")
    return int(kb)


def main():
    freeturn, source = sys.argv[1], sys.argv[2]
    job = open(os.path.join(source, "configs/jobs/oap_segment.yaml")).read()
    # ASan keeps freed memory in quarantine: a small one, so that RSS shows what is held.
    os.environ["ASAN_OPTIONS"] = os.environ.get("ASAN_OPTIONS", "") + ":quarantine_size_mb=1"
    fail = False
    with tempfile.TemporaryDirectory() as tmp:
        peaks = {}
        for pitch in ("0.02", "0.0025"):
            text = job.replace("pitch: 0.05", "pitch: " + pitch)
            text = "\n".join(l for l in text.splitlines() if not l.startswith("outputs:"))
            text += "\noutputs: {nc: false, cl_csv: false, mesh: false, report: false}\n"
            path = os.path.join(tmp, f"oap_{pitch}.yaml")
            with open(path, "w") as f:
                f.write(text)
            peaks[("check", pitch)] = peak_kb([freeturn, "check", path, "--quiet"])
            peaks[("run", pitch)] = peak_kb([freeturn, "run", path, "-o", os.path.join(tmp, "out"), "--quiet"])
        for mode in ("check", "run"):
            short, long_ = peaks[(mode, "0.02")], peaks[(mode, "0.0025")]
            print(f"{mode}: peak RSS {short / 1024:.1f} MB at pitch 0.02, {long_ / 1024:.1f} MB at 0.0025 (8x the points)")
            if long_ - short > 1024:
                print(f"FAIL: {mode} grows {(long_ - short) / 1024:.1f} MB with the path")
                fail = True
    sys.exit(1 if fail else 0)


if __name__ == "__main__":
    main()

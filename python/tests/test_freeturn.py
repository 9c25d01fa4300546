"""The Python module against independent values: closed forms, finite differences, and the
files the command line writes (the C++ sag of `freeturn sample`, the CL CSV, the NC
program). Run by ctest with FREETURN_CLI and FREETURN_SOURCE_DIR set and the module on
PYTHONPATH."""
import csv
import math
import json
import os
import subprocess

import numpy as np
import pytest

import freeturn

SRC = os.environ["FREETURN_SOURCE_DIR"]
CLI = os.environ["FREETURN_CLI"]
JOBS = os.path.join(SRC, "configs", "jobs")


def even_asphere(x, y, c=1 / 50.0, k=-0.8, a4=1.2e-6, a6=-3.0e-9):
    r2 = x * x + y * y
    return c * r2 / (1 + np.sqrt(1 - (1 + k) * c * c * r2)) + a4 * r2**2 + a6 * r2**3


def test_sag_on_a_grid_equals_the_closed_form_and_the_cpp_sag(tmp_path):
    s = freeturn.surface(open(os.path.join(JOBS, "demo_asphere.yaml")).read())
    assert s.type == "even_asphere" and s.outer_radius == 10.0
    x, y = np.meshgrid(np.linspace(-7, 7, 41), np.linspace(-7, 7, 41))
    z = s.sag(x, y)
    assert z.shape == x.shape
    np.testing.assert_allclose(z, even_asphere(x, y), rtol=0, atol=1e-14)
    # The C++ sag as `freeturn sample` writes it (shortest round-trip text): equal.
    subprocess.run([CLI, "sample", os.path.join(JOBS, "demo_asphere.yaml"), "-o", str(tmp_path),
                    "--grid", "9"], check=True, capture_output=True)
    rows = list(csv.DictReader(open(tmp_path / "demo_asphere.surface.csv")))
    xs = np.array([float(r["x"]) for r in rows])
    ys = np.array([float(r["y"]) for r in rows])
    assert np.array_equal(s.sag(xs, ys), np.array([float(r["z"]) for r in rows]))
    # Its normals are normalised from the gradient there: equal to the last bit or two.
    normals = s.normal(xs, ys)
    np.testing.assert_allclose(normals, [[float(r[k]) for k in ("nx", "ny", "nz")] for r in rows],
                               rtol=0, atol=1e-15)


def test_gradient_and_normal_agree_with_finite_differences():
    s = freeturn.surface({"type": "even_asphere", "radius": 50.0, "conic": -0.8, "A4": 1.2e-6},
                         outer_radius=10)
    x = np.array([0.0, 1.5, -3.25, 6.0])
    y = np.array([0.0, -2.0, 4.5, 0.5])
    h = 1e-6
    g = s.gradient(x, y)
    assert g.shape == (4, 2)
    np.testing.assert_allclose(g[:, 0], (s.sag(x + h, y) - s.sag(x - h, y)) / (2 * h), atol=1e-8)
    np.testing.assert_allclose(g[:, 1], (s.sag(x, y + h) - s.sag(x, y - h)) / (2 * h), atol=1e-8)
    n = s.normal(x, y)
    expected = np.stack([-g[:, 0], -g[:, 1], np.ones(4)], axis=1)
    expected /= np.linalg.norm(expected, axis=1)[:, None]
    np.testing.assert_allclose(n, expected, atol=1e-15)
    assert float(s.sag(np.array(0.0), np.array(0.0))) == 0.0


def test_plan_equals_the_cl_csv(tmp_path):
    job = freeturn.load_job(os.path.join(JOBS, "oap_segment.yaml"))
    assert job.name == "oap_segment" and job.outer_radius == 5.0
    path = freeturn.plan(job)
    result = freeturn.run_job(job, output_dir=str(tmp_path))
    assert result["verdict"] == "PASS"
    rows = np.loadtxt(tmp_path / "oap_segment.cl.csv", delimiter=",", skiprows=1)
    assert rows.shape == (len(path["theta_rad"]), 16)
    header = open(tmp_path / "oap_segment.cl.csv").readline().strip().split(",")
    for i, name in enumerate(header):
        # Shortest round-trip text: the CSV reads back as the very doubles planned.
        assert np.array_equal(path[name], rows[:, i]), name
    assert result["passes"][-1]["points"] == len(path["theta_rad"])


def test_run_job_writes_the_cli_nc(tmp_path):
    job_file = os.path.join(JOBS, "sinusoidal_ring.yaml")
    result = freeturn.run_job(job_file, output_dir=str(tmp_path / "py"))
    subprocess.run([CLI, "run", job_file, "-o", str(tmp_path / "cli"), "--quiet"], check=True, cwd=JOBS)
    programs = [f for f in result["files"] if f.endswith(".nc")]
    assert len(programs) == 2
    for nc in programs:
        assert open(nc, "rb").read() == open(tmp_path / "cli" / os.path.basename(nc), "rb").read()
    finish = result["passes"][-1]
    assert finish["name"] == "finish" and finish["chord_error_max_mm"] <= 1e-4
    # The warnings as records, equal to report.json's: the ring's cone point holds the nose.
    report = json.load(open(tmp_path / "py" / "sinusoidal_ring.report.json", encoding="utf-8"))
    assert result["warning_records"] == report["warnings"]
    assert [w["kind"] for w in result["warning_records"]] == ["uncut_residual", "uncut_residual"]


def test_errors_carry_their_place(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\naperture:\n  outer_radius: -2\nsurface: {type: sphere, radius: 50}\n")
    with pytest.raises(freeturn.InputError) as error:
        freeturn.load_job(str(bad))
    assert str(error.value).startswith(f"{bad}:3:17:")
    with pytest.raises(freeturn.InputError, match=r"^<surface>:1:\d+: "):
        freeturn.surface("{type: no_such_surface}")
    with pytest.raises(freeturn.InputError, match="^outer_radius: must be a finite number"):
        freeturn.surface({"type": "sphere", "radius": 20}, float("nan"))
    with pytest.raises(freeturn.InputError, match="not -1$"):
        freeturn.surface({"type": "sphere", "radius": 20}, -1.0)
    # A dict has no lines: its errors are at "<surface>", said once.
    with pytest.raises(freeturn.InputError) as error:
        freeturn.surface({"type": "sphere", "radius": float("nan")})
    assert str(error.value) == "<surface>: surface.radius must be a finite number, not 'nan'"
    # A dict that holds itself, or lists nested 100 000 deep: refused, not a crash.
    spec = {"type": "sphere", "radius": 20}
    spec["self"] = spec
    with pytest.raises(ValueError, match="more than 64 levels"):
        freeturn.surface(spec)
    deep = []
    for _ in range(100000):
        deep = [deep]
    with pytest.raises(ValueError, match="more than 64 levels"):
        freeturn.surface({"type": "sphere", "radius": 20, "x": deep})
    # Threads as the command line takes them: 0 (one per core) or 1 to 1024.
    with pytest.raises(freeturn.InputError, match="threads: must be 0"):
        freeturn.run_job(os.path.join(JOBS, "compound_eye.yaml"), str(tmp_path / "t"), -1)
    assert not (tmp_path / "t").exists()
    # A check set to error stops a run: CheckFailure, an InputError.
    cup = tmp_path / "cup.yaml"
    cup.write_text("name: cup\naperture: {outer_radius: 0.2}\n"
                   "surface: {type: sphere, radius: 2.0, decenter: {x: 0.5}}\n"
                   "tool: {nose_radius: 0.1}\nstrategy: {mode: spiral, spiral: planar, pitch: 0.01,\n"
                   "  points: {chord: {tolerance: 0.001, max_angle_deg: 5}}}\n"
                   "cutting: {spindle_rpm: 20}\nmachine: iso-lathe-xzc\n")
    with pytest.raises(freeturn.CheckFailure, match="clearance_angle_deg"):
        freeturn.check_job(str(cup))


def test_a_jobs_surface_is_the_surface_it_cuts_compensation_and_all():
    # configs/data/make_measured_compound_eye.py made the measurement with astigmatism Z6
    # 0.25 µm and trefoil Z9 0.15 µm (Noll, normalised, R_n = 4 mm); the job cuts the design
    # less 0.8 of the error registered from it. Its text gives the design alone.
    path = os.path.join(JOBS, "compound_eye_compensated.yaml")
    job = freeturn.load_job(path)
    cut = freeturn.surface(job)
    design = freeturn.surface(open(path).read())
    assert cut.outer_radius == 4.0
    x, y = np.meshgrid(np.linspace(-3.5, 3.5, 29), np.linspace(-3.5, 3.5, 29))
    inside = x * x + y * y <= 3.5**2
    x, y = x[inside], y[inside]
    rho, theta = np.hypot(x, y) / 4, np.arctan2(y, x)
    error = 0.25e-3 * np.sqrt(6) * rho**2 * np.cos(2 * theta)
    error += 0.15e-3 * np.sqrt(8) * rho**3 * np.sin(3 * theta)
    assert np.abs(design.sag(x, y) - cut.sag(x, y) - 0.8 * error).max() < 1e-6  # 1 nm
    # The surface keeps the job's alive; asked beyond where it is defined, it refuses.
    del job
    assert np.isfinite(cut.sag(np.array([1.0]), np.array([0.5]))).all()
    with pytest.raises(freeturn.InputError, match="outer_radius: the job's surface is undefined"):
        freeturn.surface(freeturn.load_job(path), 100.0)


def test_the_readme_example_runs(tmp_path):
    # The README's Python example, as a user pastes it (it had read cl["theta"], a column
    # the CL data does not have), from a folder holding the examples' configs.
    readme = open(os.path.join(SRC, "README.md")).read()
    start = readme.index("/usr/bin/python3 -c '\n") + len("/usr/bin/python3 -c '\n")
    code = readme[start:readme.index("'\n```", start)]
    os.symlink(os.path.join(SRC, "configs"), tmp_path / "configs")
    env = dict(os.environ)
    result = subprocess.run(["/usr/bin/python3", "-c", code], cwd=tmp_path, env=env,
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip().splitlines()[-1] == "PASS"


def test_simulate_equals_the_cli(tmp_path):
    # The module's simulate is the command's: the same residual file, the same figures.
    job_file = os.path.join(JOBS, "oap_segment.yaml")
    result = freeturn.simulate(job_file, output_dir=str(tmp_path / "py"), columns=180)
    cli = subprocess.run([CLI, "simulate", job_file, "-o", str(tmp_path / "cli"), "--quiet", "--columns", "180"],
                         check=True, cwd=JOBS, capture_output=True, text=True).stdout
    pv = float(cli.split("form error PV ")[1].split(" nm")[0])
    sim = result["simulation"]
    assert sim["pv_nm"] == pytest.approx(pv, abs=5e-4)  # the CLI prints 3 decimals
    assert sim["pv_nm"] == pytest.approx(sim["max_nm"] - sim["min_nm"], rel=1e-12)
    residual = "oap_segment.residual.csv"
    assert open(tmp_path / "py" / residual, "rb").read() == open(tmp_path / "cli" / residual, "rb").read()
    # The planner's prediction bounds the simulation (an upper bound within 10 %).
    assert sim["pv_nm"] <= sim["predicted_pv_nm"] <= 1.1 * sim["pv_nm"]
    assert result["verdict"] == "PASS"


def test_simulate_a_program_judges_it(tmp_path):
    # freeturn's own program read back passes; the same with one block 2 µm lower gouges
    # there, and the verdict says so.
    job_file = os.path.join(JOBS, "oap_segment.yaml")
    own = freeturn.run_job(job_file, output_dir=str(tmp_path / "own"))
    nc = [f for f in own["files"] if f.endswith(".nc")][0]
    read_back = freeturn.simulate(job_file, output_dir=str(tmp_path / "back"), program=nc)
    assert read_back["verdict"] == "PASS" and read_back["simulation"]["min_nm"] > 0
    assert read_back["simulation"]["predicted_pv_nm"] is None
    lines = open(nc).read().split("\n")
    k = [i for i, line in enumerate(lines) if line.startswith("G1 X")][200]
    words = lines[k].split()
    z = [w for w in words if w.startswith("Z")][0]
    lines[k] = lines[k].replace(z, "Z%.6f" % (float(z[1:]) - 0.002))
    moved = tmp_path / "moved.nc"
    moved.write_text("\n".join(lines))
    cut = freeturn.simulate(job_file, output_dir=str(tmp_path / "moved"), program=str(moved))
    assert cut["verdict"] == "UNSAFE"
    assert cut["simulation"]["min_nm"] < -1000
    assert [w["kind"] for w in cut["warning_records"]] == ["simulated_gouge"]
    assert cut["unsafe"][0].startswith("the simulated cut goes")
    with pytest.raises(freeturn.InputError, match="^columns: must be an even number"):
        freeturn.simulate(job_file, columns=7)
    with pytest.raises(freeturn.InputError, match="^radial_step: must be a finite number"):
        freeturn.simulate(job_file, radial_step=float("nan"))


def test_ncdiff(tmp_path):
    a = tmp_path / "a.nc"
    b = tmp_path / "b.nc"
    a.write_text("G1 X1.000000 Z0.5 C0\nG1 X0.9 Z0.5 C3\n")
    b.write_text("G01 Z0.50 X1.0 C0.0 (the same, written otherwise)\nG1 X0.9001 Z0.5 C3\n")
    d = freeturn.ncdiff(str(a), str(b))
    assert not d["same"] and d["blocks"] == (2, 2)
    assert d["first_difference"].startswith(f"{a}:2 vs {b}:2: X 0.9")
    assert d["largest"]["X"] == pytest.approx(1e-4, rel=1e-9)
    assert freeturn.ncdiff(str(a), str(b), tolerance=2e-4)["same"]
    with pytest.raises(freeturn.InputError, match="^tolerance: must be a finite number"):
        freeturn.ncdiff(str(a), str(b), tolerance=float("nan"))
    b.write_text("G1 X1 X2 Z0 C0\n")
    with pytest.raises(freeturn.InputError, match=r"b.nc:1:7: X is given twice in one block"):
        freeturn.ncdiff(str(a), str(b))

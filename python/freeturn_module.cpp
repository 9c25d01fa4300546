// freeturn from Python: jobs loaded and run, CL data as NumPy arrays, design surfaces
// evaluated over NumPy arrays. A thin layer over the library (freeturn/freeturn.hpp);
// errors become freeturn.InputError (and its subclass freeturn.CheckFailure) whose text
// starts with the file:line:col, as the command line prints it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "freeturn/core/number_text.hpp"
#include "freeturn/freeturn.hpp"
#include "freeturn/io/nc_program.hpp"
#include "freeturn/job/surface_yaml.hpp"
#include "freeturn/job/yaml_reader.hpp"

namespace py = pybind11;
using namespace freeturn;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A dict (of dicts, lists, numbers, strings, booleans) as YAML, for surface(). As deep as
// a YAML file may nest (kMaxYamlDepth): a dict that holds itself, or a list of lists a
// hundred thousand deep, is refused instead of overflowing the stack.
YAML::Node to_yaml(const py::handle& value, int depth = 0) {
  if (depth > kMaxYamlDepth)
    throw py::value_error("the surface spec nests more than " + std::to_string(kMaxYamlDepth) +
                          " levels deep (a dict or list that holds itself?)");
  if (py::isinstance<py::dict>(value)) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& [k, v] : value.cast<py::dict>())
      map[py::str(k).cast<std::string>()] = to_yaml(v, depth + 1);
    return map;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    YAML::Node list(YAML::NodeType::Sequence);
    for (const auto& v : value) list.push_back(to_yaml(v, depth + 1));
    return list;
  }
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::int_>(value)) return YAML::Node(std::to_string(value.cast<long long>()));
  if (py::isinstance<py::float_>(value)) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value.cast<double>());
    return YAML::Node(std::string(text));
  }
  return YAML::Node(py::str(value).cast<std::string>());
}

// A design surface with the aperture it was checked over.
struct PySurface {
  // Its own, or a job's (sharing the job: a compensated job's is the design less the
  // measured error).
  std::shared_ptr<const Surface> surface;
  double outer_radius = 0;
};

PySurface make_surface(const py::object& spec, double outer_radius) {
  if (!(outer_radius >= 0) || !std::isfinite(outer_radius))
    throw InputError("outer_radius",
                     "must be a finite number of mm ≥ 0 (0: the job's aperture, "
                     "or none), not " +
                         shortest_text(outer_radius));
  // A job read already: the surface it cuts, over its aperture.
  if (py::isinstance<Job>(spec)) {
    const auto job = spec.cast<std::shared_ptr<Job>>();
    if (outer_radius <= 0) outer_radius = job->aperture.outer_radius;
    if (!(outer_radius <= job->surface->defined_radius()))
      throw InputError("outer_radius", "the job's surface is undefined beyond r = " +
                                           significant_text(job->surface->defined_radius(), 6) +
                                           " mm, inside " + shortest_text(outer_radius) + " mm");
    return {std::shared_ptr<const Surface>(job, job->surface.get()), outer_radius};
  }
  YAML::Node node = py::isinstance<py::str>(spec)
                        ? load_yaml_text(spec.cast<std::string>(), "<surface>")
                        : to_yaml(spec);
  // A whole job's text or dict: its surface over its aperture.
  if (node.IsMap() && node["surface"]) {
    if (outer_radius <= 0 && node["aperture"] && node["aperture"]["outer_radius"])
      outer_radius = node["aperture"]["outer_radius"].as<double>();
    node = node["surface"];
  }
  return {surface_from_yaml(node, "<surface>", outer_radius), outer_radius};
}

// f(x, y) over two arrays of one shape (or scalars), into arrays of that shape with
// `components` values per point appended as the last axis (1: none appended).
template <class F>
py::array evaluate(const Array& x, const Array& y, int components, F&& f) {
  if (x.ndim() != y.ndim() || !std::equal(x.shape(), x.shape() + x.ndim(), y.shape()))
    throw py::value_error("x and y must have the same shape");
  std::vector<py::ssize_t> shape(x.shape(), x.shape() + x.ndim());
  if (components > 1) shape.push_back(components);
  py::array_t<double> out(shape);
  const double* xs = x.data();
  const double* ys = y.data();
  double* o = out.mutable_data();
  const py::ssize_t n = x.size();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) f(xs[i], ys[i], o + i * components);
  }
  return out;
}

std::shared_ptr<Job> job_of(const py::object& path_or_job) {
  if (py::isinstance<Job>(path_or_job)) return path_or_job.cast<std::shared_ptr<Job>>();
  return std::make_shared<Job>(load_job(py::str(path_or_job).cast<std::string>()));
}

py::dict figures(const PassFigures& f) {
  py::dict d;
  d["name"] = f.name;
  d["stock_mm"] = f.stock;
  d["points"] = f.points;
  d["revolutions"] = f.revolutions;
  d["chord_error_max_mm"] = f.chord_max;
  d["chord_error_rms_mm"] = f.chord_rms;
  d["scallop_max_mm"] = f.scallop_max;
  d["cycle_time_s"] = f.cycle_time;
  d["constant_rpm_cycle_time_s"] = f.constant_rpm_cycle_time;
  d["uncut_residual_max_mm"] = f.uncut_max;
  d["max_rpm"] = f.dynamics.max_rpm;
  return d;
}

py::dict result_dict(const RunReport& r, const std::vector<std::string>& files) {
  py::dict d;
  d["verdict"] = r.safe() ? "PASS" : "UNSAFE";
  d["unsafe"] = r.unsafe_reasons();
  d["warnings"] = r.messages();
  // The same warnings as records, from report.json's own writer (docs/report.schema.json).
  d["warning_records"] = py::module_::import("json").attr("loads")(warnings_json(r.warnings));
  d["job"] = r.job;
  d["machine"] = r.machine;
  d["spindle_rpm"] = r.spindle_rpm;
  py::list passes;
  for (const PassFigures& f : r.passes) passes.append(figures(f));
  d["passes"] = passes;
  d["files"] = files;
  return d;
}

}  // namespace

PYBIND11_MODULE(freeturn, m) {
  m.doc() = "freeturn: CAM for ultraprecision diamond turning of optical surfaces";
  m.attr("__version__") = kVersion;

  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<CheckFailure> check_failure(m, "CheckFailure", input_error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const CheckFailure& e) {
      check_failure(e.what());
    } catch (const InputError& e) {
      input_error(e.what());
    }
  });

  py::class_<Job, std::shared_ptr<Job>>(m, "Job", "A job read from its YAML file")
      .def_property_readonly("name", [](const Job& j) { return j.name; })
      .def_property_readonly("file", [](const Job& j) { return j.file; })
      .def_property_readonly("inner_radius", [](const Job& j) { return j.aperture.inner_radius; })
      .def_property_readonly("outer_radius", [](const Job& j) { return j.aperture.outer_radius; })
      .def_property_readonly("machine", [](const Job& j) { return j.plan ? j.plan->machine : ""; })
      .def("__repr__", [](const Job& j) { return "<freeturn.Job '" + j.name + "' from " + j.file + ">"; });

  m.def("load_job", [](const std::string& path) { return std::make_shared<Job>(load_job(path)); },
        py::arg("path"), "Reads and checks a job file; errors carry its file:line:col.");

  m.def(
      "run_job",
      [](const py::object& path_or_job, const std::string& output_dir, int threads, bool simulate) {
        const std::shared_ptr<Job> job = job_of(path_or_job);
        RunOptions options;
        options.output_dir = output_dir;
        options.threads = threads;
        if (simulate) {
          options.simulation = SimulationOptions{};
          options.simulation->threads = threads;
        }
        RunResult r;
        {
          py::gil_scoped_release release;
          r = run_job(*job, options);
        }
        return result_dict(r.report, r.files);
      },
      py::arg("path_or_job"), py::arg("output_dir") = ".", py::arg("threads") = 0,
      py::arg("simulate") = false,
      "Runs a job as `freeturn run` does: NC programs, CL data and the report in output_dir.\n"
      "Returns a dict: verdict ('PASS' or 'UNSAFE'), unsafe reasons, warnings, per-pass figures,\n"
      "files written. threads: that plan the spiral (and simulate, when simulate is true); 0: one\n"
      "per core. The files are the same on any number.");

  m.def(
      "simulate",
      [](const py::object& path_or_job, const std::string& output_dir, double radial_step,
         int columns, int threads, const py::object& program) {
        if (!std::isfinite(radial_step) || radial_step < 0 || radial_step > 10)
          throw InputError("radial_step",
                           "must be a finite number in [0, 10] mm (0: a sixteenth of the "
                           "pitch), not " +
                               shortest_text(radial_step));
        if (columns < 2 || columns > 1000000 || columns % 2)
          throw InputError("columns",
                           "must be an even number from 2 to 1000000 (each angle has its "
                           "opposite), not " +
                               std::to_string(columns));
        const std::shared_ptr<Job> job = job_of(path_or_job);
        SimulationOptions simulation;
        simulation.radial_step = radial_step;
        simulation.columns = columns;
        simulation.threads = threads;
        RunOptions options;
        options.output_dir = output_dir;
        options.threads = threads;
        const std::string nc =
            program.is_none() ? std::string() : py::str(program).cast<std::string>();
        RunResult r;
        {
          py::gil_scoped_release release;
          r = nc.empty() ? simulate_job(*job, simulation, options)
                         : simulate_program(*job, nc, simulation, options);
        }
        py::dict d = result_dict(r.report, r.files);
        const SimulationResult& s = *r.report.simulation;
        py::dict sim;
        sim["pv_nm"] = s.pv * 1e6;
        sim["rms_nm"] = s.rms * 1e6;
        sim["max_nm"] = s.max * 1e6;
        sim["min_nm"] = s.min * 1e6;
        sim["max_at_r_mm"] = s.max_r;
        sim["min_at_r_mm"] = s.min_r;
        sim["cells_not_reached"] = s.uncut;
        sim["predicted_pv_nm"] =
            nc.empty() ? py::object(py::float_(s.predicted.pv() * 1e6)) : py::object(py::none());
        py::list worst;
        for (const ResidualPlace& p : s.worst) {
          py::dict w;
          w["residual_nm"] = p.residual * 1e6;
          w["r_mm"] = p.r;
          w["theta_deg"] = part_degrees(p.phi);
          w["cause"] = to_string(p.cause);
          worst.append(w);
        }
        sim["worst"] = worst;
        d["simulation"] = sim;
        return d;
      },
      py::arg("path_or_job"), py::arg("output_dir") = ".", py::arg("radial_step") = 0.0,
      py::arg("columns") = 360, py::arg("threads") = 0, py::arg("program") = py::none(),
      "Runs a job and cuts its finishing pass in simulation, as `freeturn simulate` does, or\n"
      "with program=path an NC program for the job's machine (from freeturn or another CAM)\n"
      "instead of the job's own: then the verdict is UNSAFE where the simulated cut goes below\n"
      "the design or a block leaves the machine's travel. radial_step (mm, 0: a sixteenth of the\n"
      "pitch) and columns (even) set the grid. Returns run_job's dict with 'simulation': PV,\n"
      "RMS, max and min (nm, residual above the design positive), where, and the worst places.");

  m.def(
      "ncdiff",
      [](const std::string& a, const std::string& b, double tolerance) {
        if (!std::isfinite(tolerance) || tolerance < 0 || tolerance > 1e6)
          throw InputError("tolerance",
                           "must be a finite number in [0, 1e6], not " + shortest_text(tolerance));
        NcDiffOptions o;
        o.axis_tolerance = tolerance;
        const NcDiffResult r = nc_diff_files(a, b, o);
        py::dict d;
        d["same"] = r.same;
        d["first_difference"] = r.first_difference;
        d["blocks"] = py::make_tuple(r.blocks_a, r.blocks_b);
        py::dict largest;
        for (int i = 0; i < 26; ++i)
          if (r.largest[i] > 0)
            largest[py::str(std::string(1, static_cast<char>('A' + i)))] = r.largest[i];
        d["largest"] = largest;
        return d;
      },
      py::arg("a"), py::arg("b"), py::arg("tolerance") = 1e-9,
      "Compares two NC programs by what they make the machine do, as `freeturn ncdiff`\n"
      "does: each read with the point files it calls (M98), the blocks that act paired in\n"
      "the same modal state, axis words within tolerance (mm or degrees); formatting,\n"
      "comments and restated modal codes ignored (docs/verify.md). Returns\n"
      "{'same', 'first_difference', 'blocks': (a, b), 'largest': {letter: largest |Δ|}}.\n"
      "Raises InputError (file:line:col) for a file that is not NC.");

  m.def(
      "check_job",
      [](const py::object& path_or_job) {
        const std::shared_ptr<Job> job = job_of(path_or_job);
        RunReport r;
        {
          py::gil_scoped_release release;
          r = check_job(*job);
        }
        return result_dict(r, {});
      },
      py::arg("path_or_job"), "Everything run_job does but writing: the verdict and figures.");

  m.def(
      "plan",
      [](const py::object& path_or_job) {
        const std::shared_ptr<Job> job = job_of(path_or_job);
        PlannedPath path;
        {
          py::gil_scoped_release release;
          path = plan_job(*job);
        }
        const auto n = static_cast<py::ssize_t>(path.locations.size());
        py::dict out;
        std::vector<py::array_t<double>> columns;
        for (int c = 0; c < 16; ++c) columns.emplace_back(n);
        for (py::ssize_t i = 0; i < n; ++i) {
          const std::array<double, 16> v = cl_values(path.locations[static_cast<std::size_t>(i)],
                                                     path.records[static_cast<std::size_t>(i)]);
          for (std::size_t c = 0; c < 16; ++c) columns[c].mutable_data()[i] = v[c];
        }
        // The CL CSV's columns, by the same names (report/cl_file.hpp).
        for (std::size_t c = 0; c < 16; ++c) out[kClColumns[c]] = columns[c];
        return out;
      },
      py::arg("path_or_job"),
      "The finishing pass's cutter locations, planned and checked without writing files: a\n"
      "dict of NumPy arrays named as the CL CSV's columns (theta_rad, x_mm, y_mm, z_mm, nx,\n"
      "ny, nz, tx_mm, ty_mm, tz_mm, b_deg, X_mm, Z_mm, C_deg, B_deg, chord_mm).");

  py::class_<PySurface>(m, "Surface", "A design surface; lengths in mm")
      .def_property_readonly("type", [](const PySurface& s) { return std::string(s.surface->type()); })
      .def_property_readonly("outer_radius", [](const PySurface& s) { return s.outer_radius; })
      .def(
          "sag",
          [](const PySurface& s, const Array& x, const Array& y) {
            return evaluate(x, y, 1, [&](double px, double py_, double* o) { o[0] = s.surface->sag(px, py_); });
          },
          py::arg("x"), py::arg("y"), "z(x, y) over arrays of one shape")
      .def(
          "gradient",
          [](const PySurface& s, const Array& x, const Array& y) {
            return evaluate(x, y, 2, [&](double px, double py_, double* o) {
              double z = 0;
              s.surface->sag_gradient(px, py_, z, o[0], o[1]);
            });
          },
          py::arg("x"), py::arg("y"), "(∂z/∂x, ∂z/∂y) as the last axis")
      .def(
          "normal",
          [](const PySurface& s, const Array& x, const Array& y) {
            return evaluate(x, y, 3, [&](double px, double py_, double* o) {
              const Eigen::Vector3d n = s.surface->normal(px, py_);
              o[0] = n.x(), o[1] = n.y(), o[2] = n.z();
            });
          },
          py::arg("x"), py::arg("y"), "the unit normal toward the tool, (nx, ny, nz) as the last axis");

  m.def("surface", &make_surface, py::arg("spec"), py::arg("outer_radius") = 0.0,
        "A design surface from its YAML text or dict ({type: ..., parameters}), or a job's\n"
        "text, dict or freeturn.Job (its surface over its aperture; a Job's is the surface it\n"
        "cuts, with any compensation). outer_radius: the aperture it must be defined over.");
}

// _beamfea: the compiled half of the `beamfea` Python package (beamfea/__init__.py is the face
// users read: signatures, docstrings, pandas). Everything goes through io's public API,
// load_and_check and run_document, as the program does, so the answers are the program's.
//
// The GIL is held while Python objects are converted to JSON and the results back to Python,
// and released while the engine runs: threads of a ThreadPoolExecutor run cases in parallel. On
// the main thread (or with a progress callback) the engine runs on a thread of its own, so that
// Ctrl-C stops it (python/interruptible.hpp).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <optional>

#include "app/huge_pages_policy.hpp"
#include "app/openblas.hpp"
#include "app/thread_tasks.hpp"
#include "elements/section_shapes.hpp"
#include "io/lump.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "io/urdf_reader.hpp"
#include "python/convert.hpp"
#include "python/interruptible.hpp"
#include "python/python_errors.hpp"
#include "python/sweep_table_binding.hpp"
#include "solvers/petsc_solver.hpp"

namespace py = pybind11;
using namespace beamfea;
using namespace beamfea::python;

namespace {

// A model given as a dict (converted) or a path (read and parsed; errors name the file).
nlohmann::json document_of(const py::object& model) {
  if (py::isinstance<py::dict>(model)) {
    auto doc = json_from_python(model, "");
    return doc;
  }
  if (py::isinstance<py::str>(model) || py::hasattr(model, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(model));
    py::gil_scoped_release release;
    return read_json_file(path);
  }
  return json_from_python(model, "");  // a Mapping, or an InputError naming the type
}

// The ids ("id", "node") of the items of a model's top-level lists, for naming the entity of
// an error met while converting the model itself (a NaN, a set).
nlohmann::json id_skeleton(const py::handle& model) {
  nlohmann::json doc = nlohmann::json::object();
  if (!py::isinstance<py::dict>(model)) return doc;
  for (auto [key, value] : py::reinterpret_borrow<py::dict>(model)) {
    if (!py::isinstance<py::str>(key) || !py::isinstance<py::list>(value)) continue;
    nlohmann::json items = nlohmann::json::array();
    for (auto item : py::reinterpret_borrow<py::list>(value)) {
      nlohmann::json ids = nlohmann::json::object();
      if (py::isinstance<py::dict>(item))
        for (const char* k : {"id", "node"})
          if (item.contains(k)) {
            py::object v = item[k];
            if (py::isinstance<py::str>(v)) ids[k] = v.cast<std::string>();
            else if (PyLong_Check(v.ptr()) && !PyBool_Check(v.ptr())) ids[k] = v.cast<long long>();
          }
      items.push_back(std::move(ids));
    }
    doc[key.cast<std::string>()] = std::move(items);
  }
  return doc;
}

// Every id of `only` must name an analysis of the document.
void check_ids(const nlohmann::json& doc, const std::vector<std::string>& only) {
  std::vector<std::string> ids;
  if (auto it = doc.find("analyses"); it != doc.end() && it->is_array())
    for (const auto& a : *it)
      if (a.is_object() && a.contains("id")) ids.push_back(a["id"].is_string() ? a["id"].get<std::string>() : a["id"].dump());
  for (const auto& id : only) {
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) continue;
    std::string known;
    for (const auto& k : ids) known += (known.empty() ? "" : ", ") + k;
    throw InputError("/analyses", "no analysis with id '" + id + "' (the model has: " + (known.empty() ? "none" : known) + ")");
  }
}

py::object run(const py::object& model, const std::vector<std::string>& only, const py::object& specs,
               const std::optional<std::string>& out, bool vtk, const py::object& progress_callback) {
  nlohmann::json doc;
  try {
    doc = document_of(model);
    if (!specs.is_none()) doc["analyses"] = json_from_python(specs, "/analyses");
  } catch (const InputError& e) {
    nlohmann::json ids = id_skeleton(model);
    if (!specs.is_none()) ids["analyses"] = id_skeleton(py::dict(py::arg("analyses") = specs))["analyses"];
    raise_input_error(e, &ids);
  }
  RunReport report;
  std::atomic<bool> cancel{false};
  Progress progress;
  const bool want_progress = !progress_callback.is_none();
  try {
    // On a thread of its own, Ctrl-C and the progress callback served meanwhile (python/interruptible.hpp).
    run_interruptible(
        [&] {
          const Model m = load_and_check(doc);
          check_ids(doc, only);
          progress.total = only.empty() ? doc.at("analyses").size() : only.size();
          RunOptions options;
          if (out) options.out_dir = *out;
          options.write_vtk = vtk;
          options.only = only;
          options.cancel = &cancel;
          options.analyses_done = &progress.done;
          if (want_progress) options.progress = [&](const std::string& line) { progress.set_message(line); };
          // As the program does: a large results.json formatted on all cores (app/thread_tasks.hpp;
          // a small one, as in a ThreadPoolExecutor of many cases, starts no threads).
          if (out) options.parallel = app::thread_tasks();
          report = run_document(m, doc, options);
        },
        cancel, progress, progress_callback);
  } catch (const InputError& e) {
    raise_input_error(e, &doc);
  }
  return python_from_json(report.results);
}

// A model given from Python as a JSON document; an error names the field with the model's ids.
nlohmann::json model_document(const py::object& model) {
  try {
    return document_of(model);
  } catch (const InputError& e) {
    const nlohmann::json ids = id_skeleton(model);
    raise_input_error(e, &ids);
  }
}

py::dict check(const py::object& model) {
  const nlohmann::json doc = model_document(model);
  try {
    py::gil_scoped_release release;
    const Model m = load_and_check(doc);
    py::gil_scoped_acquire acquire;
    py::dict d;
    d["nodes"] = m.nodes.size();
    d["elements"] = m.elements.size();
    d["members"] = m.members.size();
    d["joints"] = m.joints.size();
    return d;
  } catch (const InputError& e) {
    raise_input_error(e, &doc);
  }
}

// A URDF file (and a side-car: none, a dict or a path) as a model document, returned as JSON text
// (beamfea/__init__.py makes it plain Python objects).
std::string urdf_model(const std::string& path, const py::object& sidecar) {
  std::optional<nlohmann::json> car;
  std::string car_source;
  try {
    if (!sidecar.is_none()) {
      car = document_of(sidecar);
      car_source = py::isinstance<py::dict>(sidecar) ? "(dict)" : "'" + std::string(py::str(py::module_::import("os").attr("fspath")(sidecar))) + "'";
    }
    py::gil_scoped_release release;
    return urdf_file_to_model(path, car, car_source).dump();
  } catch (const InputError& e) {
    raise_input_error(e, nullptr);
  }
}

// The lumped (VJM) model of a beam model (io/lump.hpp), as JSON text (the Python side parses it
// into plain lists and dicts: a model to edit and dump, not arrays).
std::string lump(const py::object& model, const py::object& links) {
  const nlohmann::json doc = model_document(model);
  nlohmann::json links_doc;
  try {
    links_doc = document_of(links);
  } catch (const InputError& e) {
    raise_input_error(e, nullptr);
  }
  try {
    py::gil_scoped_release release;
    return lump_model(doc, links_doc).dump();
  } catch (const InputError& e) {
    raise_input_error(e, e.pointer().rfind("/links", 0) == 0 ? nullptr : &doc);
  }
}

py::object sweep(const py::object& spec, int jobs, const py::object& progress) {
  nlohmann::json doc;
  std::filesystem::path directory = std::filesystem::current_path();
  try {
    if (!py::isinstance<py::dict>(spec) && (py::isinstance<py::str>(spec) || py::hasattr(spec, "__fspath__"))) {
      const std::string path = py::str(py::module_::import("os").attr("fspath")(spec));
      directory = std::filesystem::absolute(path).parent_path();
      doc = read_json_file(path);
    } else {
      doc = json_from_python(spec, "");
    }
  } catch (const InputError& e) {
    const nlohmann::json ids = id_skeleton(spec);
    raise_input_error(e, &ids);
  }
  try {
    const Sweep s = read_sweep(doc, directory);
    return sweep_columns(s, jobs, progress);
  } catch (const InputError& e) {
    raise_input_error(e, &doc);
  }
}

// The properties of a section shape (elements/section_shapes.hpp) as a dict; bad dimensions raise
// beamfea.InputError naming the dimension.
py::dict py_section_properties(const std::string& shape, const std::vector<std::pair<std::string, double>>& dimensions) {
  SectionProperties p;
  try {
    p = beamfea::section_properties(shape, dimensions);
  } catch (const std::invalid_argument& e) {
    raise_input_error(InputError("", "section shape '" + shape + "': " + e.what()), nullptr);
  }
  const PrincipalMoments pm = principal_moments(p.Iy, p.Iz, p.Iyz);
  py::dict d;
  d["A"] = p.A, d["Iy"] = p.Iy, d["Iz"] = p.Iz, d["J"] = p.J, d["ky"] = p.ky, d["kz"] = p.kz, d["Iyz"] = p.Iyz;
  d["I1"] = pm.I1, d["I2"] = pm.I2, d["principal_angle"] = pm.angle;
  return d;
}

py::list py_section_shapes() {
  py::list out;
  for (const auto& s : beamfea::section_shapes()) {
    py::dict d;
    d["shape"] = std::string(s.name);
    py::list dims, opt;
    for (const auto& k : s.dimensions) dims.append(std::string(k));
    for (const auto& k : s.optional) opt.append(std::string(k));
    d["dimensions"] = dims, d["optional"] = opt;
    d["description"] = std::string(s.description), d["formulas"] = std::string(s.formulas);
    out.append(d);
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(_beamfea, m) {
  m.doc() = "beamfea's engine (use the beamfea package, not this module)";
  m.attr("__version__") = BEAMFEA_PYTHON_VERSION;
  // As the program does at start (app/openblas.hpp): OpenBLAS's generic kernels replaced on a CPU
  // it did not recognise. At import, before this module's engine calls the BLAS.
  static const app::BlasCores blas = app::choose_openblas_core();
  // Huge pages for the large buffers unless the host takes free ones back (app/huge_pages_policy.hpp).
  app::configure_huge_pages();
  m.def("blas", [] {
    py::dict d;
    d["openblas"] = blas.openblas;
    d["core"] = blas.core;
    d["replaced"] = blas.replaced;
    return d;
  });
  init_conversions();
  register_error_translator();
  // PETSc (the iterative solver, started on first use) finalised as the interpreter exits.
  py::module_::import("atexit").attr("register")(py::cpp_function([] { finalize_petsc(); }));
  m.def("run", &run, py::arg("model"), py::arg("only"), py::arg("specs"), py::arg("out"), py::arg("vtk"), py::arg("progress"));
  m.def("check", &check, py::arg("model"));
  m.def("sweep", &sweep, py::arg("spec"), py::arg("jobs"), py::arg("progress"));
  m.def("lump", &lump, py::arg("model"), py::arg("links"));
  m.def("section_properties", &py_section_properties, py::arg("shape"), py::arg("dimensions"));
  m.def("section_shapes", &py_section_shapes);
  m.def("urdf_model", &urdf_model, py::arg("path"), py::arg("sidecar"));
}

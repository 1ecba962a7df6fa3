#include "python/convert.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.hpp"
#include "io/json_util.hpp"

namespace py = pybind11;

namespace beamfea::python {

namespace {

std::string type_name(py::handle h) { return py::str(py::type::handle_of(h).attr("__name__")); }

bool is_numpy(py::handle h, const char* what) {
  // Only look NumPy up when an object of a foreign type arrives: no import for plain documents.
  const std::string module = py::str(py::type::handle_of(h).attr("__module__"));
  if (module != "numpy") return false;
  py::module_ np = py::module_::import("numpy");
  return py::isinstance(h, np.attr(what));
}

// Deeper than any model: a dict or list that contains itself would otherwise recurse until the
// C stack overflows.
constexpr int kMaxDepth = 200;

nlohmann::json convert(py::handle h, const std::string& pointer, int depth);

}  // namespace

nlohmann::json json_from_python(py::handle h, const std::string& pointer) { return convert(h, pointer, 0); }

namespace {

nlohmann::json convert(py::handle h, const std::string& pointer, int depth) {
  if (depth > kMaxDepth) throw InputError(pointer, "nested more than " + std::to_string(kMaxDepth) + " levels deep (does it contain itself?)");
  if (h.is_none()) return nullptr;
  if (PyBool_Check(h.ptr())) return h.ptr() == Py_True;
  if (PyLong_Check(h.ptr())) {
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(h.ptr(), &overflow);
    if (overflow == 0) return static_cast<std::int64_t>(v);
    if (overflow > 0) {
      const unsigned long long u = PyLong_AsUnsignedLongLong(h.ptr());
      if (!PyErr_Occurred()) return static_cast<std::uint64_t>(u);
      PyErr_Clear();
    }
    throw InputError(pointer, "integer out of range: " + std::string(py::str(h)));
  }
  if (PyFloat_Check(h.ptr())) {
    const double x = PyFloat_AsDouble(h.ptr());
    if (!std::isfinite(x)) throw InputError(pointer, "not a finite number: " + std::string(py::str(h)));
    return x;
  }
  if (PyUnicode_Check(h.ptr())) return h.cast<std::string>();
  if (PyDict_Check(h.ptr())) {
    nlohmann::json obj = nlohmann::json::object();
    for (auto [k, v] : py::reinterpret_borrow<py::dict>(h)) {
      if (!PyUnicode_Check(k.ptr()))
        throw InputError(pointer, "keys must be strings, not " + type_name(k) + " (" + std::string(py::repr(k)) + ")");
      const std::string key = k.cast<std::string>();
      obj[key] = convert(v, json_in::child(pointer, key), depth + 1);
    }
    return obj;
  }
  if (PyList_Check(h.ptr()) || PyTuple_Check(h.ptr())) {
    nlohmann::json arr = nlohmann::json::array();
    const auto seq = py::reinterpret_borrow<py::sequence>(h);
    const std::size_t n = seq.size();
    for (std::size_t i = 0; i < n; ++i) arr.push_back(convert(seq[i], json_in::child(pointer, i), depth + 1));
    return arr;
  }
  if (is_numpy(h, "ndarray")) return convert(h.attr("tolist")(), pointer, depth + 1);
  if (is_numpy(h, "generic")) return convert(h.attr("item")(), pointer, depth + 1);
  if (py::isinstance(h, py::module_::import("collections.abc").attr("Mapping")))
    return convert(py::dict(py::reinterpret_borrow<py::object>(h)), pointer, depth + 1);
  throw InputError(pointer, "cannot be written as JSON: an object of type " + type_name(h));
}

using ojson = nlohmann::ordered_json;

bool is_leaf(const ojson& v) { return v.is_number() || v.is_null(); }

// The shape of `v` if it is a non-empty array of numbers (null allowed, at least one number),
// or a non-empty array of arrays of one such shape; empty otherwise.
std::vector<py::ssize_t> numeric_shape(const ojson& v) {
  std::vector<py::ssize_t> shape;
  for (const ojson* p = &v; p->is_array(); p = &(*p)[0]) {
    if (p->empty()) return {};
    shape.push_back(static_cast<py::ssize_t>(p->size()));
  }
  if (shape.empty()) return {};
  // Every element at depth d must be an array of shape[d] entries; the leaves numbers or null.
  bool any_number = false;
  auto conforms = [&](auto&& self, const ojson& x, std::size_t d) -> bool {
    if (d == shape.size()) {
      any_number = any_number || x.is_number();
      return is_leaf(x);
    }
    if (!x.is_array() || static_cast<py::ssize_t>(x.size()) != shape[d]) return false;
    for (const auto& e : x)
      if (!self(self, e, d + 1)) return false;
    return true;
  };
  if (!conforms(conforms, v, 0) || !any_number) return {};
  return shape;
}

void fill(const ojson& v, double*& out) {
  if (v.is_array()) {
    for (const auto& e : v) fill(e, out);
  } else {
    *out++ = v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
  }
}

}  // namespace

namespace {
// numpy.empty, looked up when the module is imported (not lazily: a function-local static
// initialised under the GIL can deadlock with a second thread) and kept for the process's life.
PyObject* numpy_empty = nullptr;
}  // namespace

void init_conversions() { numpy_empty = py::object(py::module_::import("numpy").attr("empty")).release().ptr(); }

py::object new_float_array(const std::vector<py::ssize_t>& shape, double*& data) {
  py::tuple dims(shape.size());
  for (std::size_t i = 0; i < shape.size(); ++i) dims[i] = py::int_(shape[i]);
  py::object a = py::reinterpret_borrow<py::object>(numpy_empty)(dims, "float64");
  const py::buffer_info info = py::reinterpret_borrow<py::buffer>(a).request(true);
  data = static_cast<double*>(info.ptr);
  return a;
}

py::object python_from_json(const ojson& v) {
  switch (v.type()) {
    case ojson::value_t::null:
    case ojson::value_t::discarded:
      return py::none();
    case ojson::value_t::boolean:
      return py::bool_(v.get<bool>());
    case ojson::value_t::number_integer:
      return py::int_(v.get<std::int64_t>());
    case ojson::value_t::number_unsigned:
      return py::int_(v.get<std::uint64_t>());
    case ojson::value_t::number_float: {
      const double x = v.get<double>();
      if (!std::isfinite(x)) return py::none();  // results.json writes null there
      return py::float_(x);
    }
    case ojson::value_t::string:
      return py::str(v.get_ref<const std::string&>());
    case ojson::value_t::binary:
      return py::bytes(std::string(v.get_binary().begin(), v.get_binary().end()));
    case ojson::value_t::object: {
      py::dict d;
      for (const auto& [key, x] : v.items()) d[py::str(key)] = python_from_json(x);
      return d;
    }
    case ojson::value_t::array: {
      if (const auto shape = numeric_shape(v); !shape.empty()) {
        double* out = nullptr;
        py::object a = new_float_array(shape, out);
        fill(v, out);
        return a;
      }
      py::list l(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) l[i] = python_from_json(v[i]);
      return l;
    }
  }
  return py::none();
}

}  // namespace beamfea::python

#include "python/python_errors.hpp"

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace beamfea::python {

namespace {

// RFC 6901: "~1" is "/", "~0" is "~".
std::string unescape(const std::string& token) {
  std::string s;
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (token[i] == '~' && i + 1 < token.size()) {
      s += token[i + 1] == '1' ? '/' : '~';
      ++i;
    } else {
      s += token[i];
    }
  }
  return s;
}

std::string singular(const std::string& collection) {
  if (collection == "analyses") return "analysis";
  if (collection.size() > 1 && collection.back() == 's') return collection.substr(0, collection.size() - 1);
  return collection;
}

std::string id_text(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

py::object error_class(const char* name) { return py::module_::import("beamfea._errors").attr(name); }

void set_error(const char* class_name, const py::object& instance) {
  PyErr_SetObject(error_class(class_name).ptr(), instance.ptr());
}

py::object optional_str(const std::string& s) { return s.empty() ? py::object(py::none()) : py::object(py::str(s)); }

}  // namespace

std::string entity_at(const nlohmann::json& document, const std::string& pointer) {
  // The first two tokens: a top-level collection and an index into it.
  if (pointer.size() < 2 || pointer[0] != '/') return {};
  const auto slash = pointer.find('/', 1);
  if (slash == std::string::npos) return {};
  const std::string collection = unescape(pointer.substr(1, slash - 1));
  const auto end = pointer.find('/', slash + 1);
  const std::string index = pointer.substr(slash + 1, end == std::string::npos ? std::string::npos : end - slash - 1);
  if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos) return {};
  const auto it = document.find(collection);
  if (it == document.end() || !it->is_array()) return {};
  const std::size_t i = std::stoul(index);
  if (i >= it->size()) return {};
  const auto& item = (*it)[i];
  const std::string kind = singular(collection);
  if (item.is_object()) {
    if (auto id = item.find("id"); id != item.end() && (id->is_string() || id->is_number_integer()))
      return kind + " '" + id_text(*id) + "'";
    if (auto node = item.find("node"); node != item.end() && (node->is_string() || node->is_number_integer()))
      return kind + " of node '" + id_text(*node) + "'";
  }
  return kind + " " + index;
}

namespace {

// Each sets the Python error indicator (the GIL is held).
void set_input_error(const InputError& e, const nlohmann::json* document) {
  const std::string entity = document ? entity_at(*document, e.pointer()) : std::string();
  set_error("InputError", error_class("InputError")(e.what(), optional_str(e.pointer()), optional_str(entity)));
}

void set_model_error(const ModelError& e) {
  set_error("ModelError", error_class("ModelError")(e.what(), optional_str(e.entity())));
}

void set_base_error(const Error& e) { set_error("Error", error_class("Error")(e.what())); }

}  // namespace

void raise_input_error(const InputError& e, const nlohmann::json* document) {
  set_input_error(e, document);
  throw py::error_already_set();
}

void raise_model_error(const ModelError& e) {
  set_model_error(e);
  throw py::error_already_set();
}

void raise_error(const Error& e) {
  set_base_error(e);
  throw py::error_already_set();
}

void register_error_translator() {
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      std::rethrow_exception(p);
    } catch (const InputError& e) {
      set_input_error(e, nullptr);
    } catch (const ModelError& e) {
      set_model_error(e);
    } catch (const Error& e) {
      set_base_error(e);
    }
  });
}

}  // namespace beamfea::python

#include "python/sweep_table_binding.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <thread>
#include <vector>

#include "io/sweep_table.hpp"
#include "python/convert.hpp"
#include "python/interruptible.hpp"

namespace py = pybind11;

namespace beamfea::python {

namespace {

// Stops handing out cases once `cancel` is set (the running ones finish).
std::vector<SweepCaseResult> run_cases(const Sweep& sweep, int jobs, const std::atomic<bool>& cancel, Progress& progress) {
  const std::size_t n = sweep.size();
  std::vector<SweepCaseResult> results(n);
  if (jobs <= 0) jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  jobs = static_cast<int>(std::max<std::size_t>(1, std::min<std::size_t>(jobs, n)));
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    SweepWorkspace workspace(sweep);  // this thread's document, model and results, case after case
    for (std::size_t i = next++; i < n && !cancel.load(std::memory_order_relaxed); i = next++) {
      run_sweep_case(sweep, i, {}, workspace, results[i]);
      progress.done.fetch_add(1);
    }
  };
  std::vector<std::thread> workers;
  for (int w = 1; w < jobs; ++w) workers.emplace_back(work);
  work();
  for (auto& t : workers) t.join();
  return results;
}

// A cell of the table as a number, if it is one ("" is NaN).
std::optional<double> number(const std::string& cell) {
  if (cell.empty()) return std::numeric_limits<double>::quiet_NaN();
  char* end = nullptr;
  const double x = std::strtod(cell.c_str(), &end);
  if (end != cell.c_str() + cell.size()) return std::nullopt;
  return x;
}

// A float64 ndarray when every cell is a number or empty, else a list of str (None if empty).
py::object column(const std::vector<std::string>& cells) {
  std::vector<double> values;
  values.reserve(cells.size());
  for (const auto& c : cells) {
    const auto x = number(c);
    if (!x) {
      py::list l;
      for (const auto& s : cells) l.append(s.empty() ? py::object(py::none()) : py::object(py::str(s)));
      return l;
    }
    values.push_back(*x);
  }
  double* out = nullptr;
  py::object a = new_float_array({static_cast<py::ssize_t>(values.size())}, out);
  std::copy(values.begin(), values.end(), out);
  return a;
}

// A parameter column: numbers (null: NaN) as float64, anything else as a list of Python values.
py::object parameter_column(const std::vector<nlohmann::ordered_json>& values) {
  bool numeric = true;
  for (const auto& v : values) numeric = numeric && (v.is_number() || v.is_null());
  if (numeric) {
    double* out = nullptr;
    py::object a = new_float_array({static_cast<py::ssize_t>(values.size())}, out);
    for (const auto& v : values) *out++ = v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
    return a;
  }
  py::list l;
  for (const auto& v : values) l.append(python_from_json(v));
  return l;
}

}  // namespace

py::dict sweep_columns(const Sweep& sweep, int jobs, const py::object& progress_callback) {
  std::vector<SweepCaseResult> results;
  std::atomic<bool> cancel{false};
  Progress progress;
  progress.total = sweep.size();
  progress.set_message("sweep of " + std::to_string(sweep.size()) + " cases");
  run_interruptible([&] { results = run_cases(sweep, jobs, cancel, progress); }, cancel, progress, progress_callback);
  const std::size_t n = results.size();
  py::dict table;
  py::list ids;
  for (std::size_t i = 0; i < n; ++i) ids.append(sweep.case_id(i));
  table["case"] = ids;

  std::vector<std::vector<nlohmann::ordered_json>> params(sweep.parameter_names.size());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < params.size(); ++k) params[k].emplace_back(sweep.parameter(i, k));
  for (std::size_t k = 0; k < params.size(); ++k) table[py::str(sweep.parameter_names[k])] = parameter_column(params[k]);

  // Output columns as in DIR/cases.csv (docs/sweep.md): those of the first case that ends ok,
  // or the output's name alone when none does; other cases fill the columns they share.
  const auto first_ok = std::find_if(results.begin(), results.end(),
                                     [](const SweepCaseResult& r) { return r.status == SweepCaseResult::Status::Succeeded; });
  const SweepColumns columns = beamfea::sweep_columns(sweep, first_ok != results.end() ? &*first_ok : nullptr);
  for (std::size_t o = 0; o < sweep.outputs.size(); ++o) {
    const std::vector<std::string>& names = columns.outputs[o];
    std::map<std::string, std::vector<std::string>> cells;
    for (const auto& name : names) cells.emplace(name, std::vector<std::string>(n));
    for (std::size_t i = 0; i < n; ++i)
      for (const auto& [name, text] : results[i].outputs[o])
        if (auto it = cells.find(name); it != cells.end()) it->second[i] = text;
    for (const auto& name : names) table[py::str(name)] = column(cells[name]);
  }

  py::list status, message;
  double* wall_data = nullptr;
  py::object wall = new_float_array({static_cast<py::ssize_t>(n)}, wall_data);
  for (std::size_t i = 0; i < n; ++i) {
    status.append(to_string(results[i].status));
    message.append(results[i].message);
    wall_data[i] = results[i].wall_time_s;
  }
  table["status"] = status;
  table["message"] = message;
  table["wall_time_s"] = wall;
  return table;
}

}  // namespace beamfea::python

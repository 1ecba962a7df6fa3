#pragma once
// A sweep (io/sweep.hpp) run in process into columns instead of a CSV file: the same cases, the
// same column names and order as DIR/cases.csv (case, parameters, flattened outputs, status,
// message, wall_time_s), numeric columns as float64 ndarrays (NaN where a cell is empty).
#include <pybind11/pybind11.h>

#include "io/sweep.hpp"

namespace beamfea::python {

// Runs every case on `jobs` threads (0: all cores) with the GIL released; returns a dict of
// columns in table order. Ctrl-C stops it after the running cases (KeyboardInterrupt);
// `progress` (None: none) is called as progress(cases done, cases, message)
// (python/interruptible.hpp).
pybind11::dict sweep_columns(const Sweep& sweep, int jobs, const pybind11::object& progress);

}  // namespace beamfea::python

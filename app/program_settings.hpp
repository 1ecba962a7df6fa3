#pragma once
// The settings a program makes once at start, before any analysis: the one place that lists them,
// so that the CLI and the benchmarks (which measure what the CLI runs) make the same ones.
#include <string>

#include "app/huge_pages_policy.hpp"
#include "app/openblas.hpp"

namespace beamfea::app {

struct ProgramSettings {
  BlasCores blas;              // the BLAS kernels (openblas.hpp)
  bool openmp_serial = false;  // the libraries' OpenMP regions on one thread (openmp.hpp)
  HugePageChoice huge_pages;   // huge pages for the large buffers or not (huge_pages_policy.hpp)
};

// In this order: the BLAS kernels (before anything calls the BLAS), the libraries' OpenMP (before
// a library opens a parallel region), the prefault thread for very large blocks (prefault.hpp),
// the huge-page advice. Call first in main. (The Python module makes only the BLAS and huge-page
// choices: python/module.cpp.)
ProgramSettings configure_program();

// "OpenBLAS, SkylakeX kernels (OpenBLAS chose Prescott on this CPU; ...)": the BLAS line of
// --version and of the benchmarks' output.
std::string describe(const BlasCores& blas);

}  // namespace beamfea::app

// The BLAS kernels and the libraries' OpenMP threads of a benchmark: chosen as the program chooses
// them (app/openblas.hpp, app/openmp.hpp), so that a benchmark measures what `beamfea` runs, and
// named in its output.
#pragma once

#include <string>

#include "app/openblas.hpp"
#include "app/openmp.hpp"

namespace beamfea::bench {

// Call first in main. "OpenBLAS SkylakeX kernels (replacing Prescott); OpenMP regions on one
// thread", or what else is loaded or set.
inline std::string choose_libraries_as_the_program() {
  const auto blas = app::choose_openblas_core();
  const std::string openmp = app::serialize_library_openmp() ? "; OpenMP regions on one thread" : "";
  if (!blas.openblas) return "not OpenBLAS with runtime kernel selection" + openmp;
  return "OpenBLAS " + blas.core + " kernels" + (blas.replaced.empty() ? "" : " (replacing " + blas.replaced + ")") + openmp;
}

}  // namespace beamfea::bench

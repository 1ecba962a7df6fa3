// The BLAS kernels, the libraries' OpenMP threads, the huge-page advice and the prefault thread of a
// benchmark: chosen as the program chooses them (app/openblas.hpp, app/openmp.hpp,
// app/huge_pages_policy.hpp, app/prefault.hpp), so that a benchmark measures what `beamfea` runs,
// and named in its output.
#pragma once

#include <string>

#include "app/huge_pages_policy.hpp"
#include "app/openblas.hpp"
#include "app/openmp.hpp"
#include "app/prefault.hpp"

namespace beamfea::bench {

// Call first in main. "OpenBLAS SkylakeX kernels (replacing Prescott); OpenMP regions on one
// thread; huge pages advised (...)", or what else is loaded or set.
inline std::string choose_libraries_as_the_program() {
  const auto blas = app::choose_openblas_core();
  const std::string openmp = app::serialize_library_openmp() ? "; OpenMP regions on one thread" : "";
  const std::string huge_pages = "; huge pages " + app::configure_huge_pages().reason;
  app::install_background_prefault();
  if (!blas.openblas) return "not OpenBLAS with runtime kernel selection" + openmp + huge_pages;
  return "OpenBLAS " + blas.core + " kernels" + (blas.replaced.empty() ? "" : " (replacing " + blas.replaced + ")") + openmp +
         huge_pages;
}

}  // namespace beamfea::bench

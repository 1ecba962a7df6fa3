// The BLAS kernels of a benchmark: chosen as the program chooses them (app/openblas.hpp), so that a
// benchmark measures what `beamfea` runs, and named in its output.
#pragma once

#include <string>

#include "app/openblas.hpp"

namespace beamfea::bench {

// Call first in main. "OpenBLAS SkylakeX kernels (replacing Prescott)", or what else is loaded.
inline std::string choose_blas_kernels() {
  const auto blas = app::choose_openblas_core();
  if (!blas.openblas) return "not OpenBLAS with runtime kernel selection";
  return "OpenBLAS " + blas.core + " kernels" + (blas.replaced.empty() ? "" : " (replacing " + blas.replaced + ")");
}

}  // namespace beamfea::bench

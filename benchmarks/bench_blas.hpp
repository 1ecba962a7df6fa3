// The BLAS kernels, the libraries' OpenMP threads, the prefault thread and the huge-page advice of
// a benchmark: chosen as the program chooses them (app/program_settings.hpp), so that a benchmark
// measures what `beamfea` runs, and named in its output.
#pragma once

#include <string>

#include "app/program_settings.hpp"

namespace beamfea::bench {

// Call first in main. "OpenBLAS, SkylakeX kernels; OpenMP regions on one thread; huge pages
// advised (...)", or what else is loaded or set.
inline std::string choose_libraries_as_the_program() {
  const auto settings = app::configure_program();
  return app::describe(settings.blas) + (settings.openmp_serial ? "; OpenMP regions on one thread" : "") +
         "; huge pages " + settings.huge_pages.reason;
}

}  // namespace beamfea::bench

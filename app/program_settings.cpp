#include "app/program_settings.hpp"

#include "app/openmp.hpp"
#include "app/prefault.hpp"

namespace beamfea::app {

ProgramSettings configure_program() {
  ProgramSettings s;
  s.blas = choose_openblas_core();
  s.openmp_serial = serialize_library_openmp();
  install_background_prefault();
  s.huge_pages = configure_huge_pages();
  return s;
}

std::string describe(const BlasCores& blas) {
  if (!blas.openblas) return "not OpenBLAS with runtime kernel selection";
  std::string s = "OpenBLAS, " + blas.core + " kernels";
  if (!blas.replaced.empty())
    s += " (OpenBLAS chose " + blas.replaced + " on this CPU; OPENBLAS_CORETYPE chooses otherwise)";
  return s;
}

}  // namespace beamfea::app

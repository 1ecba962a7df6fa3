#pragma once
// The OpenBLAS of the process: which kernels it chose, and the one correction a program (the CLI,
// the Python module) makes once at start, before any analysis.
//
// OpenBLAS builds with DYNAMIC_ARCH (Debian's) pick their kernels at load time from the CPU model.
// Before 0.3.25 a model the library does not know fell back to the generic "Prescott" kernels
// (SSE3) whatever the CPU could do (fixed upstream: github.com/OpenMathLib/OpenBLAS/pull/4268). Debian 12
// ships 0.3.21: on this project's Xeon (family 6, model 207) dgemm ran at 6-10 GFlop/s on one core
// instead of 45-69 GFlop/s with the AVX-512 kernels, and every large factorisation was that much
// slower (docs/performance.md, "The BLAS"). When the library reports Prescott, nobody chose it
// (OPENBLAS_CORETYPE unset) and the CPU has AVX2 or AVX-512, the program reinitialises OpenBLAS
// with the kernels the CPU supports, through OpenBLAS's own OPENBLAS_CORETYPE mechanism
// (gotoblas_dynamic_quit / gotoblas_dynamic_init read it again). A user who sets OPENBLAS_CORETYPE
// keeps their choice; another BLAS (reference, BLIS, MKL) is left as it is.
#include <optional>
#include <string>

namespace beamfea::app {

// What the CPU offers, as the kernel choice needs it.
struct CpuVectorUnits {
  bool avx2_fma = false;
  bool avx512 = false;  // AVX-512 F, DQ, BW and VL, enabled by the operating system
};
CpuVectorUnits cpu_vector_units();

// The OpenBLAS core (an OPENBLAS_CORETYPE value) to switch to, or none: only when OpenBLAS chose
// "Prescott" by itself (`coretype_set` false) on a CPU with AVX2 + FMA ("Haswell") or AVX-512
// ("SkylakeX").
std::optional<std::string> better_openblas_core(const std::string& current_core, bool coretype_set,
                                                const CpuVectorUnits& cpu);

struct BlasCores {
  bool openblas = false;  // an OpenBLAS with runtime kernel selection is loaded
  std::string core;       // its kernels now (openblas_get_corename), empty if not OpenBLAS
  std::string replaced;   // the kernels it had chosen, when the program switched them; else empty
};

// Reports the loaded OpenBLAS's kernels and switches them when better_openblas_core says so.
// Call once, at start, before any thread calls the BLAS.
BlasCores choose_openblas_core();

// The solvers' BLAS-thread hook (solvers/blas_threads.hpp) on OpenBLAS, when it is the BLAS loaded.
void install_openblas_threads_hook();

// Sets OpenBLAS's number of threads (nothing when another BLAS is loaded). The one place where the
// program (a sweep: cases are its unit of parallelism) and the benchmarks set it.
void set_blas_threads(int threads);

}  // namespace beamfea::app

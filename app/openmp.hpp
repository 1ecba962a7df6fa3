#pragma once
// The OpenMP regions of the numerical libraries: the one setting the program (the CLI) makes once
// at start, beside the BLAS's (app/openblas.hpp).
//
// Debian's CHOLMOD clears and fills its large supernodes in OpenMP loops on four threads, a
// constant of its build (CHOLMOD_OMP_NUM_THREADS) whatever the machine, while OpenBLAS's threads
// already hold the cores for the BLAS calls between those loops. On the 2-core machine measured,
// CHOLMOD's threads spun against OpenBLAS's: 18,000-21,000 context switches in one run of 21,504
// DOFs (35 without), and the process 0.81 s against 0.72-0.76 s (docs/performance.md, "OpenMP
// threads"). The program therefore runs the libraries' parallel regions on their calling thread
// (omp_set_max_active_levels(0)), unless the user set one of OpenMP's variables, which then decide
// as usual. The Python module does not: in a Python process other libraries may share the OpenMP
// runtime, and the setting would be theirs too (OMP_MAX_ACTIVE_LEVELS=0 in the environment does
// the same there).
namespace beamfea::app {

// Whether one of the variables that size OpenMP teams (OMP_NUM_THREADS, OMP_THREAD_LIMIT,
// OMP_MAX_ACTIVE_LEVELS, OMP_DYNAMIC) is set in `environment` ("NAME=value" entries, null-ended).
bool user_sets_openmp(const char* const* environment);

// One thread per parallel region of the loaded OpenMP runtime (GCC's libgomp for Debian's CHOLMOD,
// found without linking one into the program), unless user_sets_openmp(environ) or no runtime is
// loaded. Returns whether it set it. Call once, at start, before any thread runs an analysis.
bool serialize_library_openmp();

// The setting belongs to the calling thread (OpenMP 5.1 made max-active-levels-var a data-environment
// ICV, and GCC's libgomp keeps it per thread): a thread started afterwards (a sweep's worker) begins
// with the runtime's defaults. Such a thread calls this first; it repeats the program's choice, and
// does nothing where serialize_library_openmp() was not called or did nothing (a Python process).
void apply_library_openmp_to_this_thread();

}  // namespace beamfea::app

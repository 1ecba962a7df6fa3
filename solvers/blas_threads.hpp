#pragma once
// BLAS threads: a process-wide setting that belongs to the program (cli/), not to the solvers; this
// is only the hook through which a solver asks for fewer of them.
//
// OpenBLAS's worker threads spin (sched_yield) for a while after each threaded call before they
// sleep. A solver that makes many small factorisations (a path: a few thousand DOFs, one every few
// milliseconds) keeps them spinning for its whole run and gains little from them: measured in
// docs/performance.md "Path following". Such a solver holds a SingleBlasThread while it runs: one
// BLAS thread, the previous number restored when it ends. Without an installed hook (a library user,
// the Python module) the BLAS is left as it is.
#include <functional>

namespace beamfea {

// Sets the number of BLAS threads and returns the previous number.
using BlasThreadsHook = std::function<int(int threads)>;

// Installs the hook (the program, once, before any analysis runs; empty: none).
void install_blas_threads_hook(BlasThreadsHook hook);

// One BLAS thread for the holder's lifetime, through the installed hook (nothing without one).
class SingleBlasThread {
 public:
  SingleBlasThread();
  ~SingleBlasThread();
  SingleBlasThread(const SingleBlasThread&) = delete;
  SingleBlasThread& operator=(const SingleBlasThread&) = delete;

 private:
  int previous_ = 0;  // 0: nothing to restore
};

}  // namespace beamfea

#include "solvers/blas_threads.hpp"

#include <utility>

namespace beamfea {

namespace {
BlasThreadsHook& hook() {
  static BlasThreadsHook h;
  return h;
}
}  // namespace

void install_blas_threads_hook(BlasThreadsHook h) { hook() = std::move(h); }

SingleBlasThread::SingleBlasThread() {
  if (hook()) previous_ = hook()(1);
}

SingleBlasThread::~SingleBlasThread() {
  if (hook() && previous_ > 1) hook()(previous_);
}

}  // namespace beamfea

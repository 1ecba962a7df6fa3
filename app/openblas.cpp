#include "app/openblas.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <strings.h>

#include "solvers/blas_threads.hpp"

namespace beamfea::app {

namespace {

// A symbol of the loaded OpenBLAS. The program's libraries are global (RTLD_DEFAULT finds them);
// in a Python extension they were loaded locally, so the libraries are also asked by name,
// without loading anything (RTLD_NOLOAD). dlsym on a library's handle searches its dependencies
// too: Debian's libblas.so.3 of OpenBLAS forwards to libopenblas.so.0.
void* openblas_symbol(const char* name) {
  if (void* s = dlsym(RTLD_DEFAULT, name)) return s;
  for (const char* lib : {"libopenblas.so.0", "libblas.so.3"}) {
    if (void* handle = dlopen(lib, RTLD_LAZY | RTLD_NOLOAD)) {
      void* s = dlsym(handle, name);
      dlclose(handle);  // drops the reference RTLD_NOLOAD took; the library stays loaded
      if (s) return s;
    }
  }
  return nullptr;
}

using CoreName = char* (*)();
using Hook = void (*)();

}  // namespace

CpuVectorUnits cpu_vector_units() {
  CpuVectorUnits cpu;
#if defined(__x86_64__) || defined(__i386__)
  // GCC's checks include the operating system's support for the registers (XCR0).
  __builtin_cpu_init();
  cpu.avx2_fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  cpu.avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
#endif
  return cpu;
}

std::optional<std::string> better_openblas_core(const std::string& current_core, bool coretype_set,
                                                const CpuVectorUnits& cpu) {
  if (coretype_set || strcasecmp(current_core.c_str(), "prescott") != 0) return std::nullopt;
  if (cpu.avx512) return "SkylakeX";
  if (cpu.avx2_fma) return "Haswell";
  return std::nullopt;
}

BlasCores choose_openblas_core() {
  BlasCores out;
  const auto core_name = reinterpret_cast<CoreName>(openblas_symbol("openblas_get_corename"));
  const auto quit = reinterpret_cast<Hook>(openblas_symbol("gotoblas_dynamic_quit"));
  const auto init = reinterpret_cast<Hook>(openblas_symbol("gotoblas_dynamic_init"));
  if (!core_name || !quit || !init) return out;  // not OpenBLAS, or built for one CPU only
  out.openblas = true;
  out.core = core_name();
  const auto better = better_openblas_core(out.core, std::getenv("OPENBLAS_CORETYPE") != nullptr, cpu_vector_units());
  if (!better) return out;
  // OPENBLAS_CORETYPE only while OpenBLAS reads it: the process's environment (and its
  // children's) stays as the user left it.
  setenv("OPENBLAS_CORETYPE", better->c_str(), 1);
  quit();
  init();
  unsetenv("OPENBLAS_CORETYPE");
  out.replaced = out.core;
  out.core = core_name();
  return out;
}

void set_blas_threads(int threads) {
  using Set = void (*)(int);
  if (const auto set = reinterpret_cast<Set>(openblas_symbol("openblas_set_num_threads"))) set(threads);
}

void install_openblas_threads_hook() {
  using Set = void (*)(int);
  using Get = int (*)();
  const auto set = reinterpret_cast<Set>(openblas_symbol("openblas_set_num_threads"));
  const auto get = reinterpret_cast<Get>(openblas_symbol("openblas_get_num_threads"));
  if (!set || !get) return;
  install_blas_threads_hook([set, get](int threads) {
    const int previous = get();
    if (threads != previous) set(threads);
    return previous;
  });
}

}  // namespace beamfea::app

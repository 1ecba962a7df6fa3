#include "app/openmp.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <string_view>

namespace beamfea::app {

namespace {

using SetMaxActiveLevels = void (*)(int);
// The runtime's omp_set_max_active_levels once serialize_library_openmp() has used it.
std::atomic<SetMaxActiveLevels> g_chosen{nullptr};

}  // namespace

bool user_sets_openmp(const char* const* environment) {
  if (!environment) return false;
  for (const char* const* e = environment; *e; ++e)
    for (std::string_view name : {"OMP_NUM_THREADS=", "OMP_THREAD_LIMIT=", "OMP_MAX_ACTIVE_LEVELS=", "OMP_DYNAMIC="})
      if (std::strncmp(*e, name.data(), name.size()) == 0) return true;
  return false;
}

bool serialize_library_openmp() {
  if (user_sets_openmp(environ)) return false;
  void* symbol = dlsym(RTLD_DEFAULT, "omp_set_max_active_levels");
  if (!symbol) {
    // A runtime loaded with local scope (under a host that loaded the libraries so): asked by
    // name, loading nothing.
    if (void* handle = dlopen("libgomp.so.1", RTLD_LAZY | RTLD_NOLOAD)) {
      symbol = dlsym(handle, "omp_set_max_active_levels");
      dlclose(handle);  // drops RTLD_NOLOAD's reference; the library stays loaded
    }
  }
  if (!symbol) return false;
  // OpenMP 5.1, 2.6.1: with max-active-levels-var 0 no parallel region is active, so each team is
  // its calling thread alone.
  const auto set = reinterpret_cast<SetMaxActiveLevels>(symbol);
  set(0);
  g_chosen = set;
  return true;
}

void apply_library_openmp_to_this_thread() {
  if (const SetMaxActiveLevels set = g_chosen.load()) set(0);
}

}  // namespace beamfea::app

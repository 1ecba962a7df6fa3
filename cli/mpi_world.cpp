#include "cli/mpi_world.hpp"

#include <algorithm>
#include <cstdlib>

#include "solvers/petsc_solver.hpp"

#ifdef BEAMFEA_HAVE_MPI
#include <mpi.h>
#endif

namespace beamfea::cli {

int launched_ranks() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(var)) return std::max(1, std::atoi(v));
  return 1;
}

int ranks_on_this_host(int ranks) {
  if (const char* l = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE")) return std::max(1, std::atoi(l));
  return ranks;
}

#ifdef BEAMFEA_HAVE_MPI
MpiWorld::MpiWorld(Threads threads) {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, threads == Threads::MainOnly ? MPI_THREAD_FUNNELED : MPI_THREAD_SERIALIZED,
                  &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiWorld::~MpiWorld() {
  finalize_petsc();  // PETSc (and SLEPc), when something solved iteratively, runs on this MPI
  MPI_Finalize();
}

int MpiWorld::max_over_ranks(int value) const {
  int out = value;
  MPI_Allreduce(&value, &out, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return out;
}

int MpiWorld::from_rank_0(int value) const {
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value;
}

void MpiWorld::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return; should it, this process ends all the same
}
#endif

}  // namespace beamfea::cli

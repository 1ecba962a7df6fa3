#pragma once
// The program's MPI: detected from the launcher's environment (mpirun sets OMPI_COMM_WORLD_SIZE,
// other launchers PMI_SIZE or PMIX_SIZE), started by the program (MPI_Init) only when it is one
// of several processes, and ended by it (PETSc first, then MPI_Finalize). Two commands use it:
// `sweep` distributes cases (each process solves cases of its own) and `run` distributes one
// model's DOFs (every process takes part in each iterative solve). Process-wide, hence here in
// the program and never in a library.
#include <memory>
#include <string>

namespace beamfea::cli {

// Number of processes the launcher started, from its environment (1 when not under mpirun).
int launched_ranks();

// Processes of this run on this host, from the launcher (OpenMPI); `ranks` when it does not say.
int ranks_on_this_host(int ranks);

#ifdef BEAMFEA_HAVE_MPI
class MpiWorld {
 public:
  // How the threads of a process call MPI: only the main thread (a sweep: its workers never call
  // MPI), or any thread one at a time (a run: PETSc's calls take petsc_lock(), whichever thread
  // makes them).
  enum class Threads { MainOnly, Serialized };
  explicit MpiWorld(Threads threads);
  // finalize_petsc (PETSc runs on this MPI), then MPI_Finalize.
  ~MpiWorld();
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Collective: the largest of every process's `value`.
  int max_over_ranks(int value) const;
  // Collective: rank 0's `value` on every process.
  int from_rank_0(int value) const;
  // Ends every process of the job with exit code `code` (MPI_Abort): a process that cannot go on
  // while the others may wait for it in a collective call.
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
};
#endif

}  // namespace beamfea::cli

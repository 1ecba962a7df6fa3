#pragma once
// The hook through which the engine runs independent pieces of work at once: the linear analysis
// (solvers/linear_static.hpp: the element matrices beside the matrix's pattern and ordering) and io
// (formatting a large results.json in slices: io/json_writer.hpp). Threads are a process-wide
// matter that belongs to the program, not to the engine: the program (cli/, python/) passes an
// implementation (app/thread_tasks.hpp) through the options; without one (empty: a library user,
// a sweep's workers, which already run cases on threads) everything runs on the calling thread, in
// order.
#include <cstddef>
#include <functional>

namespace beamfea {

// Runs task(0), ..., task(count - 1), possibly several at once and in any order, and returns when
// all that were started have finished. An exception thrown by a task is rethrown by the call after
// the others have finished (tasks not yet started may then be skipped). The tasks of one call must
// not depend on each other; a task must not call the hook again.
using ParallelTasks = std::function<void(std::size_t count, const std::function<void(std::size_t)>& task)>;

// Runs the tasks through `parallel`, or on the calling thread in index order when it is empty.
inline void run_tasks(const ParallelTasks& parallel, std::size_t count, const std::function<void(std::size_t)>& task) {
  if (parallel) {
    parallel(count, task);
    return;
  }
  for (std::size_t i = 0; i < count; ++i) task(i);
}

}  // namespace beamfea

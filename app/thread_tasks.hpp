#pragma once
// The program's ParallelTasks (core/parallel_tasks.hpp): the threads with which `beamfea run`
// computes a linear analysis's element matrices beside the ordering of its stiffness's pattern
// (solvers/linear_static.cpp) and formats a large results.json (io/json_writer.hpp), where the
// machine's other core would otherwise sit idle.
//
// Each call starts its threads and joins them before it returns (some tens of microseconds a
// thread): meant for work of milliseconds per call, not a pool for fine-grained tasks. The calling
// thread is one of the workers, so one thread (a single core, or count 1) starts none; tasks are
// taken in index order by whichever thread is free. A thread that cannot be started leaves its
// share to the others.
#include "core/parallel_tasks.hpp"

namespace beamfea::app {

// Tasks on up to `threads` threads, the calling one included (0: std::thread::hardware_concurrency(),
// at least 1).
ParallelTasks thread_tasks(unsigned threads = 0);

}  // namespace beamfea::app

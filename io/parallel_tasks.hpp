#pragma once
// io's side of the ParallelTasks hook (core/parallel_tasks.hpp): the program passes its threads
// through RunOptions::parallel (io/run.hpp).
#include "core/parallel_tasks.hpp"

#include "app/thread_tasks.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace beamfea::app {

namespace {

void run_on_threads(std::size_t count, const std::function<void(std::size_t)>& task, unsigned threads) {
  const std::size_t n = std::min<std::size_t>(count, threads);
  if (n <= 1) {
    for (std::size_t i = 0; i < count; ++i) task(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex error_mutex;
  std::exception_ptr error;  // the first exception of a task
  auto work = [&] {
    while (!failed.load(std::memory_order_relaxed)) {
      const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= count) return;
      try {
        task(i);
      } catch (...) {
        const std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  {
    std::vector<std::jthread> workers;  // joined when the block ends, also when starting one throws
    workers.reserve(n - 1);
    try {
      for (std::size_t k = 0; k + 1 < n; ++k) workers.emplace_back(work);
    } catch (const std::system_error&) {
      // No more threads to be had (a resource limit): those started and this one do the rest.
    }
    work();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace

ParallelTasks thread_tasks(unsigned threads) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  return [threads](std::size_t count, const std::function<void(std::size_t)>& task) {
    run_on_threads(count, task, threads);
  };
}

}  // namespace beamfea::app

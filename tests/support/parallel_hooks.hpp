#pragma once
// ParallelTasks hooks (core/parallel_tasks.hpp) for tests of what runs in parallel: the
// contract at its most concurrent, and in an order no implementation uses.
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace beamfea::test {

// Every task on a thread of its own, exceptions rethrown after all have joined: the hook's
// contract at its most concurrent, independent of app/'s implementation. `calls` counts the
// hook's calls (shared by copies).
struct ThreadPerTask {
  std::shared_ptr<std::size_t> calls = std::make_shared<std::size_t>(0);
  void operator()(std::size_t count, const std::function<void(std::size_t)>& task) const {
    ++*calls;
    std::mutex m;
    std::exception_ptr error;
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < count; ++i)
      threads.emplace_back([&, i] {
        try {
          task(i);
        } catch (...) {
          const std::lock_guard lock(m);
          if (!error) error = std::current_exception();
        }
      });
    for (auto& t : threads) t.join();
    if (error) std::rethrow_exception(error);
  }
};

// The tasks on the calling thread, last first: what is formatted must not depend on their order.
inline void last_first(std::size_t count, const std::function<void(std::size_t)>& task) {
  for (std::size_t i = count; i-- > 0;) task(i);
}

}  // namespace beamfea::test

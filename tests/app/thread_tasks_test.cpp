// The program's ParallelTasks (app/thread_tasks.hpp): every index run exactly once, tasks really
// at once on the threads asked for, one thread = the calling thread in order, and a task's
// exception rethrown by the call once every started task has finished.
#include "app/thread_tasks.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace parallel_tasks_test {

using beamfea::app::thread_tasks;

TEST(ParallelTasks, RunsEveryIndexExactlyOnce) {
  for (const unsigned threads : {0u, 1u, 2u, 3u, 8u})
    for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{7}, std::size_t{10000}}) {
      std::vector<std::atomic<int>> runs(count);
      thread_tasks(threads)(count, [&](std::size_t i) { runs.at(i).fetch_add(1); });
      for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(runs[i].load(), 1) << "threads " << threads << ", count " << count << ", index " << i;
    }
}

TEST(ParallelTasks, RunsTasksAtOnceOnTheThreadsAskedFor) {
  // Three tasks that each wait until all three have started: they finish only if they run at once
  // (on three threads, the caller one of them); the wait is bounded so that a failure cannot hang.
  std::mutex m;
  std::condition_variable all_started;
  int started = 0;
  bool met = true;
  std::vector<std::thread::id> ids(3);
  thread_tasks(3)(3, [&](std::size_t i) {
    ids[i] = std::this_thread::get_id();
    std::unique_lock lock(m);
    ++started;
    all_started.notify_all();
    if (!all_started.wait_for(lock, std::chrono::seconds(20), [&] { return started == 3; })) met = false;
  });
  EXPECT_TRUE(met);
  EXPECT_NE(ids[0], ids[1]);
  EXPECT_NE(ids[1], ids[2]);
  EXPECT_NE(ids[0], ids[2]);
}

TEST(ParallelTasks, OneThreadIsTheCallerInOrder) {
  std::vector<std::size_t> order;
  const auto caller = std::this_thread::get_id();
  bool elsewhere = false;
  thread_tasks(1)(5, [&](std::size_t i) {
    order.push_back(i);
    elsewhere = elsewhere || std::this_thread::get_id() != caller;
  });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_FALSE(elsewhere);
}

TEST(ParallelTasks, AnExceptionIsRethrownAfterEveryStartedTaskHasFinished) {
  for (const unsigned threads : {1u, 4u}) {
    std::atomic<int> running{0}, finished{0};
    std::atomic<bool> overlap_at_return{false};
    try {
      thread_tasks(threads)(200, [&](std::size_t i) {
        ++running;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        --running;
        ++finished;
        if (i == 17) throw std::runtime_error("task 17");
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 17");
      overlap_at_return = running.load() != 0;
    }
    EXPECT_FALSE(overlap_at_return) << threads << " threads";
    EXPECT_GE(finished.load(), 18);  // tasks 0-17 were all taken before 17 threw, and all finish
    EXPECT_LT(finished.load(), 200);  // the rest is skipped once a task has failed
  }
}

}  // namespace parallel_tasks_test

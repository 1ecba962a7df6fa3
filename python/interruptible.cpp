#include "python/interruptible.hpp"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <thread>

namespace py = pybind11;

namespace beamfea::python {

namespace {
// How long the waiting thread sleeps between its signal checks: a Ctrl-C is seen within this
// (the engine then stops at its next cancellation check).
constexpr auto kSignalPoll = std::chrono::milliseconds(50);
// The progress callback is called at most this often while the progress changes...
constexpr auto kProgressInterval = std::chrono::milliseconds(200);
// ...and at least this often while it does not (a long single step still shows life).
constexpr auto kProgressHeartbeat = std::chrono::milliseconds(1000);

bool on_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}
}  // namespace

void Progress::set_message(std::string message) {
  std::lock_guard lock(mutex_);
  message_ = std::move(message);
}

std::string Progress::message() const {
  std::lock_guard lock(mutex_);
  return message_;
}

void run_interruptible(const std::function<void()>& work, std::atomic<bool>& cancel, const Progress& progress,
                       const py::object& callback) {
  if (callback.is_none() && !on_main_thread()) {
    py::gil_scoped_release release;
    work();
    return;
  }
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard lock(mutex);
    finished = true;
    finished_cv.notify_all();
  });
  // Joins the worker however this function ends (after cancel is set on a Python exception).
  struct Join {
    std::thread& t;
    std::atomic<bool>& cancel;
    ~Join() {
      if (!t.joinable()) return;
      cancel.store(true);
      py::gil_scoped_release release;
      t.join();
    }
  } join{worker, cancel};

  using Clock = std::chrono::steady_clock;
  auto last_call = Clock::now();
  std::size_t last_done = 0;
  std::string last_message;
  const auto report = [&](bool force) {
    if (callback.is_none()) return;
    const auto now = Clock::now();
    const std::size_t done = progress.done.load();
    std::string message = progress.message();
    const bool changed = done != last_done || message != last_message;
    if (!force && !(changed && now - last_call >= kProgressInterval) && now - last_call < kProgressHeartbeat) return;
    last_call = now;
    last_done = done;
    last_message = message;
    callback(done, progress.total.load(), message);
  };
  for (;;) {
    bool done_now;
    {
      py::gil_scoped_release release;
      std::unique_lock lock(mutex);
      done_now = finished_cv.wait_for(lock, kSignalPoll, [&] { return finished; });
    }
    if (done_now) break;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Join cancels and waits
    report(false);
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (failure) std::rethrow_exception(failure);
  report(true);
}

}  // namespace beamfea::python

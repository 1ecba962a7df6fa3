#pragma once
// Long engine calls that behave like Python: the engine runs on a thread of its own with the GIL
// released while the calling thread waits for it in short slices, and between slices (holding the
// GIL) checks for signals (Ctrl-C raises KeyboardInterrupt within a slice) and calls the user's
// progress callback. On a Python exception (KeyboardInterrupt, an exception of the callback) the
// engine is told to stop through its cancel flag, joined, and the exception raised: the
// interpreter stays usable and the engine's staged files are removed (io/atomic_file.hpp).
#include <pybind11/pybind11.h>

#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace beamfea::python {

// Where a long call stands, written by the engine's threads, read by the waiting thread.
struct Progress {
  std::atomic<std::size_t> done{0}, total{0};
  void set_message(std::string message);
  std::string message() const;

 private:
  mutable std::mutex mutex_;
  std::string message_;
};

// Runs `work` as the header says. `work` must stop soon after `cancel` is set (the engine polls
// it). `callback` (None: none) is called as callback(done, total, message) from the calling
// thread: when the progress changes (at most every kProgressInterval) and at least once a
// second, and once at the end. An exception of `work` is rethrown on the calling thread. Called
// with the GIL held. Off the main thread (a ThreadPoolExecutor's worker, where no signal can
// arrive) and without a callback, `work` runs on the calling thread with the GIL released.
void run_interruptible(const std::function<void()>& work, std::atomic<bool>& cancel, const Progress& progress,
                       const pybind11::object& callback);

}  // namespace beamfea::python

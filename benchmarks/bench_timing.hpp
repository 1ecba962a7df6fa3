// Timing helpers of the benchmarks (bench_small_models, bench_chain_rate, bench_path_step,
// bench_frame_solve, bench_modal_solve).
#pragma once

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

namespace beamfea::bench {

// The median of v (the mean of the two middle values for an even count; NaN for none).
inline double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// The calling thread's CPU seconds: on a loaded machine wall clock measures the scheduler.
inline double thread_cpu_s() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// CPU seconds of the whole process (all threads).
inline double process_cpu_s() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Wall-clock and process CPU seconds since construction. On a shared machine the CPU time of a
// single-threaded stage is the better measure of its cost; wall time is what a user waits.
struct Stopwatch {
  std::chrono::steady_clock::time_point wall0 = std::chrono::steady_clock::now();
  double cpu0 = process_cpu_s();
  double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count(); }
  double cpu() const { return process_cpu_s() - cpu0; }
};

// CPU seconds per call of each function: batches of calls sized to about budget / 5 seconds, the
// functions interleaved batch by batch (so a slow phase of the machine slows all of them), the
// median of 5 batches. per_call[i] (default 1) divides a call of fs[i] that runs several cases.
inline std::vector<double> paired(const std::vector<std::function<void()>>& fs, double budget,
                                  std::vector<double> per_call = {}) {
  per_call.resize(fs.size(), 1.0);
  std::vector<long> reps(fs.size(), 1);
  for (std::size_t i = 0; i < fs.size(); ++i) {
    const double t0 = thread_cpu_s();
    fs[i]();
    reps[i] = std::max<long>(1, static_cast<long>(budget / 5 / std::max(1e-7, thread_cpu_s() - t0)));
  }
  std::vector<std::vector<double>> t(fs.size());
  for (int b = 0; b < 5; ++b)
    for (std::size_t i = 0; i < fs.size(); ++i) {
      const double t0 = thread_cpu_s();
      for (long r = 0; r < reps[i]; ++r) fs[i]();
      t[i].push_back((thread_cpu_s() - t0) / static_cast<double>(reps[i]) / per_call[i]);
    }
  std::vector<double> med;
  for (auto& v : t) {
    std::sort(v.begin(), v.end());
    med.push_back(v[2]);
  }
  return med;
}

// paired's timing over `rounds` batch rounds, with each function's time divided by that of
// fs[reference] in the same round: the median, least and largest of those ratios. Rounds follow
// each other within milliseconds, so a change of the host's speed between them (a neighbour's load,
// the clock) moves both times of a ratio, where the ratio of two medians mixes rounds.
struct PairedTimes {
  std::vector<double> median;                               // seconds per call, median over the rounds
  std::vector<double> ratio_median, ratio_min, ratio_max;  // / fs[reference], round by round
};
inline PairedTimes paired_rounds(const std::vector<std::function<void()>>& fs, double budget,
                                 std::vector<double> per_call, std::size_t reference, int rounds) {
  per_call.resize(fs.size(), 1.0);
  std::vector<long> reps(fs.size(), 1);
  for (std::size_t i = 0; i < fs.size(); ++i) {
    fs[i]();  // once before the calibration: first-call costs (caches, lazily built state) excluded
    const double t0 = thread_cpu_s();
    fs[i]();
    reps[i] = std::max<long>(1, static_cast<long>(budget / rounds / std::max(1e-7, thread_cpu_s() - t0)));
  }
  std::vector<std::vector<double>> t(fs.size()), ratio(fs.size());
  for (int b = 0; b < rounds; ++b) {
    for (std::size_t i = 0; i < fs.size(); ++i) {
      const double t0 = thread_cpu_s();
      for (long r = 0; r < reps[i]; ++r) fs[i]();
      t[i].push_back((thread_cpu_s() - t0) / static_cast<double>(reps[i]) / per_call[i]);
    }
    for (std::size_t i = 0; i < fs.size(); ++i) ratio[i].push_back(t[i].back() / t[reference].back());
  }
  PairedTimes out;
  for (std::size_t i = 0; i < fs.size(); ++i) {
    out.median.push_back(median(t[i]));
    out.ratio_median.push_back(median(ratio[i]));
    out.ratio_min.push_back(*std::min_element(ratio[i].begin(), ratio[i].end()));
    out.ratio_max.push_back(*std::max_element(ratio[i].begin(), ratio[i].end()));
  }
  return out;
}

}  // namespace beamfea::bench

// Writing results.json against the analysis it reports (the aim: writing results.json under 10 %
// of the analysis at 202,752 DOFs).
//
//   python3 benchmarks/cube_frame.py 15x15x14 /tmp/cube.json    # 21,504 DOFs
//   build/benchmarks/bench_results_write /tmp/cube.json [reps]
//
// Runs the model's analyses in process once (no files), then times, alternately, four writers of
// the same results object into a temporary folder: nlohmann's dump(2) to a string + the atomic
// write (the baseline), write_results_json to a string + the same write, write_results_json_file
// (streamed in chunks) on one thread, and the same with the program's threads
// (app/thread_tasks.hpp: what `beamfea run` does); checks that the threaded text is the
// serial one byte for byte; prints the bytes, the times (thread CPU of the calling thread, process
// CPU and wall, median of the repetitions) and their ratios to the analysis (process CPU and wall).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <vector>

#include "bench_blas.hpp"
#include "app/thread_tasks.hpp"
#include "bench_timing.hpp"
#include "io/atomic_file.hpp"
#include "io/json_writer.hpp"
#include "io/run.hpp"

namespace {

double process_cpu_s() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
double wall_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
  fmt::print(stderr, "BLAS: {}\n", beamfea::bench::choose_libraries_as_the_program());  // as `beamfea` runs
  using namespace beamfea;
  if (argc < 2) {
    fmt::print(stderr, "usage: {} model.json [reps]\n", argv[0]);
    return 2;
  }
  const int reps = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  std::ifstream in(argv[1]);
  const nlohmann::json document = nlohmann::json::parse(in);
  const Model model = load_and_check(document);
  const double c0 = process_cpu_s(), w0 = wall_s();
  const RunReport report = run_document(model, document, RunOptions{});
  const double analysis_cpu = process_cpu_s() - c0, analysis_wall = wall_s() - w0;

  const auto dir = std::filesystem::temp_directory_path() / fmt::format("bench_results_write_{}", getpid());
  std::filesystem::create_directories(dir);
  const ParallelTasks threads = app::thread_tasks();
  {
    std::string serial, threaded;
    write_results_json(report.results, serial);
    write_results_json(report.results, threaded, threads);
    if (serial != threaded) {
      fmt::print(stderr, "the threaded text differs from the serial one\n");
      return 1;
    }
  }
  constexpr int kWriters = 4;
  std::vector<double> cpu[kWriters], pcpu[kWriters], wall[kWriters];
  std::uintmax_t bytes[kWriters] = {};
  for (int r = 0; r < reps; ++r)
    for (int k = 0; k < kWriters; ++k) {
      const auto path = dir / "results.json";
      const double t0 = bench::thread_cpu_s(), p0 = process_cpu_s(), v0 = wall_s();
      if (k >= 2) {
        write_results_json_file(report.results, path, k == 3 ? threads : ParallelTasks());
      } else {
        std::string text;
        if (k == 0) text = report.results.dump(2);
        else write_results_json(report.results, text);
        text += '\n';
        write_text_atomic(path, text);
      }
      cpu[k].push_back(bench::thread_cpu_s() - t0);
      pcpu[k].push_back(process_cpu_s() - p0);
      wall[k].push_back(wall_s() - v0);
      bytes[k] = std::filesystem::file_size(path);
    }
  std::filesystem::remove_all(dir);

  fmt::print("{}: {} nodes, {} elements; analysis {:.3f} s process CPU, {:.3f} s wall\n", argv[1],
             model.nodes.size(), model.elements.size(), analysis_cpu, analysis_wall);
  fmt::print("| writer (text and atomic file write) | MB | thread CPU s | process CPU s | wall s | / analysis CPU | / analysis wall | / before, CPU | / streamed, wall |\n"
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  const char* names[kWriters] = {"nlohmann dump(2) to a string (baseline)", "write_results_json to a string",
                                 "write_results_json_file (streamed, one thread)",
                                 "write_results_json_file (streamed, threads: now)"};
  for (int k = 0; k < kWriters; ++k)
    fmt::print("| {} | {:.1f} | {:.4f} | {:.4f} | {:.4f} | {:.3f} | {:.3f} | {:.2f} | {:.2f} |\n", names[k],
               static_cast<double>(bytes[k]) / 1e6, bench::median(cpu[k]), bench::median(pcpu[k]), bench::median(wall[k]),
               bench::median(pcpu[k]) / analysis_cpu, bench::median(wall[k]) / analysis_wall, bench::median(pcpu[k]) / bench::median(pcpu[0]),
               bench::median(wall[k]) / bench::median(wall[2]));
  return 0;
}

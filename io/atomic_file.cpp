#include "io/atomic_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <vector>
#include <fstream>

#include "core/errors.hpp"

namespace beamfea {

namespace {
std::filesystem::path temporary_for(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  return path.string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}
}  // namespace

void write_atomic(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& writer) {
  const auto tmp = temporary_for(path);
  try {
    writer(tmp);
    std::filesystem::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

void write_text_atomic(const std::filesystem::path& path, const std::string& text) {
  write_atomic(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error("cannot write '" + tmp.string() + "'");
    out << text;
    out.close();
    if (!out) throw Error("error writing '" + tmp.string() + "'");
  });
}

StagingDir::StagingDir(std::filesystem::path out_dir) : out_(std::move(out_dir)) {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  if (!std::filesystem::exists(out_, ec)) {
    std::filesystem::create_directories(out_);
    created_out_ = true;
  } else if (!std::filesystem::is_directory(out_, ec)) {
    throw Error("output folder '" + out_.string() + "' exists and is not a folder");
  }
  staging_ = out_ / (".beamfea-staging-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::create_directory(staging_);
}

StagingDir::~StagingDir() {
  if (committed_) return;
  std::error_code ec;
  std::filesystem::remove_all(staging_, ec);
  if (created_out_) std::filesystem::remove(out_, ec);  // only when empty
}

void StagingDir::commit(const std::string& last) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(staging_)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::stable_partition(files.begin(), files.end(), [&](const auto& f) { return f.filename() != last; });
  for (const auto& f : files) {
    const auto target = out_ / f.filename();
    if (std::filesystem::is_directory(target) && !std::filesystem::is_directory(f))
      throw Error("cannot write '" + target.string() + "': a folder of that name is in the way");
    std::filesystem::rename(f, target);
  }
  std::filesystem::remove(staging_);
  committed_ = true;
}

}  // namespace beamfea

#include "io/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
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

}  // namespace beamfea

#pragma once
// Files of the tests: temporary folders, writing and reading text and JSON, and the paths of the
// repository's own files (examples, the fuzz corpus).
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamfea::test {

// A fresh temporary folder for one test.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("beamfea_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

// The whole file, byte for byte ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The JSON document of a file; a file that cannot be opened throws, naming it.
inline nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) throw std::runtime_error("cannot open " + p.string());
  return nlohmann::json::parse(in);
}

// A file or folder of the repository, from its path relative to the repository's root.
inline std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(BEAMFEA_SOURCE_DIR) / relative;
}

// The regular files of `dir` whose names end in `extension` ("": all), sorted by path.
inline std::vector<std::filesystem::path> files_in(const std::filesystem::path& dir, const std::string& extension = "") {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.is_regular_file() && (extension.empty() || e.path().extension() == extension)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace beamfea::test

#pragma once
// Files are written whole or not at all: write to "<name>.tmp-<pid>", then rename.
#include <filesystem>
#include <functional>
#include <string>

namespace beamfea {

// Writes `text` to `path` atomically; throws beamfea::Error on failure.
void write_text_atomic(const std::filesystem::path& path, const std::string& text);

// Calls writer(temporary_path) and renames the result onto `path`; removes the temporary on failure.
void write_atomic(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& writer);

// A run's outputs are staged: written into a hidden folder inside the output folder and moved
// into place only when the run ends (commit), so that a run stopped by bad input leaves the
// output folder exactly as it was. Without commit, the destructor removes the staging folder,
// and the output folder too when this object created it (and nothing else was put there).
class StagingDir {
 public:
  explicit StagingDir(std::filesystem::path out_dir);
  ~StagingDir();
  StagingDir(const StagingDir&) = delete;
  StagingDir& operator=(const StagingDir&) = delete;

  const std::filesystem::path& path() const { return staging_; }
  // Moves every staged file into the output folder (replacing files of the same name), the file
  // named `last` after all others (results.json: it appears only once the files it names are
  // there), then removes the staging folder.
  void commit(const std::string& last);

 private:
  std::filesystem::path out_;
  std::filesystem::path staging_;
  bool created_out_ = false;
  bool committed_ = false;
};

}  // namespace beamfea

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

}  // namespace beamfea

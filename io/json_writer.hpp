#pragma once
// The results writer: results.json as people and programs read it, written in one pass.
//
// Objects are indented by two spaces per level, one member per line, as nlohmann's dump(2) does;
// arrays whose elements are all scalars (numbers, strings, booleans, nulls) are written on one
// line, `[1.0, -2.5e-07, 0.0]`, so that a displacement or an end force reads as one line and
// results.json is about half the bytes of dump(2) (most of its bytes were the indentation of
// numbers, one per line). Numbers are the shortest text that reads back to the same double
// (std::to_chars), with ".0" added to integral values so that they stay floating point for
// readers that care; non-finite numbers are written as null, as nlohmann does. To a file the
// text is streamed: it is never whole in memory.
//
// With a ParallelTasks hook (core/parallel_tasks.hpp), an object or array of many structured members
// (the nodes, the elements of a large model) is formatted in windows of a few megabytes, each cut
// into slices formatted at once into strings of their own and then appended in order: the text is
// byte for byte the serial one, and still streamed. Small results start no tasks.
//
// With DeferredParts (io/deferred_results.hpp), each placeholder in `value` is written as the
// object its part makes member by member, exactly as the same object held in the tree.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io/deferred_results.hpp"
#include "core/parallel_tasks.hpp"

namespace beamfea {

// Appends the text of `value` to `out` (no trailing newline). `parallel` empty: on this thread.
void write_results_json(const nlohmann::ordered_json& value, std::string& out, const ParallelTasks& parallel = {},
                        const DeferredParts* deferred = nullptr);

// Writes the text of `value` and a newline to `path` atomically (io/atomic_file.hpp), streamed in
// chunks of about a megabyte; throws beamfea::Error when the file cannot be written. An exception
// (from the file or from a task of `parallel`) leaves no file at `path`.
void write_results_json_file(const nlohmann::ordered_json& value, const std::filesystem::path& path,
                             const ParallelTasks& parallel = {}, const DeferredParts* deferred = nullptr);

}  // namespace beamfea

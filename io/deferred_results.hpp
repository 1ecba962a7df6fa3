#pragma once
// Parts of results.json made while the file is written instead of held in the results tree.
//
// A linear analysis of a 21,504-DOF frame holds about a million numbers in its nodes' and members'
// objects. Built as one ordered_json tree they are over a million heap nodes (about 45 MB, a fifth
// of the process's memory) that the program allocates, faults in, walks once to write the file,
// and never reads again. When the caller reads only the file (`beamfea run`: RunOptions::
// results_in_memory false), an analysis may instead defer such an object: the results
// tree holds a placeholder where it goes, and the writer (io/json_writer.hpp) has its members
// made one at a time into a small tree that is reused, writing each as it would have written it
// from the whole tree. The text is the same byte for byte; only the memory it passes through is
// not.
#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace beamfea {

// Receives one member of a deferred object: its key and its value, both valid only until it
// returns.
using MemberSink = std::function<void(std::string_view key, const nlohmann::ordered_json& value)>;

// An object of results.json whose members are made on demand.
struct DeferredMembers {
  std::size_t size = 0;   // number of members
  // Makes members [first, end) in order, handing each to `emit`. It may be called several times
  // (the writer, the check for non-finite numbers) and at once on several threads for disjoint
  // ranges, so everything it writes into is its own (a range's scratch, on its stack).
  std::function<void(std::size_t first, std::size_t end, const MemberSink& emit)> make;
  // Optional: whether every number the members would hold is finite, answered from what they are
  // made of without making them (a run checks its results for overflow before writing them,
  // io/run.cpp). Empty: the members are made and looked at.
  std::function<bool()> all_finite;
};

// The deferred parts of one run's results tree, each standing in the tree as a placeholder (a
// binary value, which no JSON result can hold, whose subtype is the part's index).
class DeferredParts {
 public:
  // Keeps `part` and sets `slot` to its placeholder.
  void defer(nlohmann::ordered_json& slot, DeferredMembers part);
  // The part `v` stands for, or null when `v` is not a placeholder of these parts.
  const DeferredMembers* find(const nlohmann::ordered_json& v) const;
  // Removes every member of `v` (recursively) that is a placeholder: what the results tree is
  // left as once the parts have been written.
  void erase_placeholders(nlohmann::ordered_json& v) const;
  std::size_t size() const { return parts_.size(); }

 private:
  std::vector<DeferredMembers> parts_;
};

}  // namespace beamfea

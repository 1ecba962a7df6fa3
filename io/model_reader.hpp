#pragma once
// Reading a model from JSON (docs/input-format.md): parse, validate, mesh.
// Every error is an InputError carrying the JSON pointer of the field at fault and naming the
// entity (node, element, joint...). Nothing is analysed here.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model.hpp"
#include "io/json_pointer.hpp"

namespace beamfea {

// Parses JSON text; malformed JSON becomes an InputError naming the byte offset.
nlohmann::json parse_json_text(const std::string& text, const std::string& source);
// The largest input file read (1 GiB): JSON of about 5e6 beams, beyond any model one factorisation
// solves (docs/input-format.md).
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 30;
// Reads and parses a file: a regular file of at most kMaxInputFileBytes, else an InputError
// naming it (a device such as /dev/zero, a folder, a pipe).
// A model file's relative link-model paths (joints' "stiffness_from_model": {"model": "link.json"})
// are made relative to the file's folder (resolve_link_model_paths with the file's folder).
nlohmann::json read_json_file(const std::string& path);
// Rewrites every relative "model" path of the joints' "stiffness_from_model" in `doc` as `folder`/path
// (nothing when `folder` is empty: paths stay relative to the working folder).
void resolve_link_model_paths(nlohmann::json& doc, const std::filesystem::path& folder);

// Builds the model from a parsed document (the "analyses" entry is not read here).
Model read_model(const nlohmann::json& doc);

// Reads documents into one model again and again (a sweep worker's, case after case): each read
// builds its items out of the storage of the read before (vectors, ids, joint axes, id indexes:
// core/model.hpp, recycled), so that reading a model of the same shape allocates nothing. The
// model is read_model's, bit for bit.
class ModelBuffer {
 public:
  // As read_model(doc); valid until the next read. After an InputError the buffer holds a partly
  // read model: read again before using it.
  const Model& read(const nlohmann::json& doc);
  const Model& model() const { return model_; }

 private:
  Model model_;  // the last read
  Model spare_;  // the read before: lends its items' storage to the next read
  std::string what_;  // the reader's names of items in messages (kept: reader::ReadState::what)
};

// The node index for a node id given as a JSON value at `pointer`; throws InputError if unknown.
int node_ref(const Model& m, const nlohmann::json& v, const json_in::Pointer& pointer);
int joint_ref(const Model& m, const nlohmann::json& v, const json_in::Pointer& pointer);

}  // namespace beamfea

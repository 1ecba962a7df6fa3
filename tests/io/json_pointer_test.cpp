// json_in::Pointer (io/json_pointer.hpp): the lazily rendered JSON pointer of the readers. Its text
// must be exactly RFC 6901's (section 3: '~' written "~0", '/' written "~1", array indices in
// decimal), as the eager string concatenation it replaced wrote it, however deep and however it
// was copied.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/json_pointer.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"

namespace beamfea::json_in::json_pointer_test {
namespace {

TEST(JsonPointer, RendersRootKeysAndIndices) {
  EXPECT_EQ(Pointer().str(), "");
  EXPECT_EQ(Pointer("/nodes").str(), "/nodes");
  EXPECT_EQ(child("/nodes", 3).str(), "/nodes/3");
  EXPECT_EQ(child(child("/elements", 0), "nodes").str(), "/elements/0/nodes");
  EXPECT_EQ(child(Pointer(), "loads").child(12).child("force").child(2).str(), "/loads/12/force/2");
  const std::string root = "/analyses/1";
  EXPECT_EQ(child(root, "stop").str(), "/analyses/1/stop");
  EXPECT_EQ(static_cast<std::string>(child(root, 0)), "/analyses/1/0");
}

TEST(JsonPointer, EscapesTildeAndSlashAndKeepsEmptyKeys) {
  // RFC 6901 section 3 and its examples (section 5): "a/b" -> "/a~1b", "m~n" -> "/m~0n", "" -> "/".
  EXPECT_EQ(child(Pointer(), "a/b").str(), "/a~1b");
  EXPECT_EQ(child(Pointer(), "m~n").str(), "/m~0n");
  EXPECT_EQ(child(Pointer(), "").str(), "/");
  EXPECT_EQ(child(Pointer(), "~/~1").str(), "/~0~1~01");
  const std::string key = "x/y";
  EXPECT_EQ(child(child("/p", key), 7).str(), "/p/x~1y/7");
}

TEST(JsonPointer, CopiesAreIndependentOfTheirParents) {
  // A child keeps its own copy of the segments: the parent may be a temporary, or change later.
  Pointer kept = child(child(child("/a", 1), "b"), 2);
  Pointer p = child("/x", 0);
  const Pointer q = child(p, "y");
  p = child("/z", 5);
  EXPECT_EQ(kept.str(), "/a/1/b/2");
  EXPECT_EQ(q.str(), "/x/0/y");
  EXPECT_EQ(p.str(), "/z/5");
}

TEST(JsonPointer, DeeperThanItsInlineSegmentsRendersOnce) {
  // Beyond kMaxSegments the pointer owns its rendered root; copies share it and may outlive the
  // Pointer they were made from.
  std::string expected = "/r";
  Pointer p("/r");
  std::vector<Pointer> all;
  for (int i = 0; i < 3 * Pointer::kMaxSegments + 1; ++i) {
    if (i % 2 == 0) {
      p = p.child(static_cast<std::size_t>(i));
      expected += '/';
      expected += std::to_string(i);
    } else {
      p = p.child("k~/");
      expected += "/k~0~1";
    }
    all.push_back(p);
    EXPECT_EQ(p.str(), expected) << i;
  }
  const Pointer last = all.back();
  all.clear();
  EXPECT_EQ(last.str(), expected);
}

TEST(JsonPointer, ErrorsNameTheRenderedPointer) {
  const json doc = json::parse(R"({"a": [1, "x", {"b/c": true}]})");
  try {
    (void)number(doc["a"][1], child(child(Pointer(), "a"), 1), "value");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.pointer(), "/a/1");
    EXPECT_EQ(std::string(e.what()), "/a/1: value: expected a number");
  }
  try {
    (void)require(doc["a"][2], child(child(Pointer(), "a"), 2), "d", "thing 'T'");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.pointer(), "/a/2/d");
    EXPECT_EQ(std::string(e.what()), "/a/2/d: thing 'T': missing field 'd'");
  }
  try {
    expect_keys(doc["a"][2], child(child(Pointer(), "a"), 2), {"b"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.pointer(), "/a/2/b~1c");
  }
}

TEST(JsonPointer, ModelErrorsKeepTheirPointers) {
  // The reader's messages through the lazy pointers (a member's unknown material, a node's
  // non-numeric coordinate), as docs/input-format.md describes them.
  json m = json::parse(R"({
    "nodes": [{"id": "A", "xyz": [0, 0, 0]}, {"id": "B", "xyz": [1, 0, 0]}],
    "materials": [{"id": "s", "E": 2e11, "G": 8e10}],
    "sections": [{"id": "c", "A": 1e-3, "Iy": 1e-6, "Iz": 1e-6, "J": 2e-6}],
    "elements": [{"id": "e1", "type": "beam", "nodes": ["A", "B"], "material": "steel", "section": "c"}]
  })");
  try {
    (void)read_model(m);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/elements/0/material: element 'e1': unknown material 'steel'");
  }
  m["elements"][0]["material"] = "s";
  m["nodes"][1]["xyz"][2] = "0";
  try {
    (void)read_model(m);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nodes/1/xyz/2: node 'B' xyz: expected a number");
  }
}

}  // namespace
}  // namespace beamfea::json_in::json_pointer_test

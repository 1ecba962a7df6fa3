// Reading JSON text (io/model_reader.hpp, parse_json_text): the nesting limit where it was, strict
// parsing, and the same document as nlohmann's own parser.
#include <gtest/gtest.h>


#include "core/errors.hpp"
#include "io/model_reader.hpp"
#include "support/errors.hpp"
#include "support/files.hpp"

namespace json_text_test {

using beamfea::InputError;
using beamfea::parse_json_text;
using nlohmann::json;

namespace {

std::string nested(int containers) { return std::string(containers, '[') + std::string(containers, ']'); }

std::string message_of(const std::string& text) {
  const auto e = beamfea::test::thrown<InputError>([&] { parse_json_text(text, "t.json"); });
  return e ? e->what() : "";
}

}  // namespace

// A container inside at most 64 others is accepted (65 levels), one more level is refused.
TEST(JsonText, NestingLimitIsSixtyFourEnclosingContainers) {
  EXPECT_EQ(message_of(nested(65)), "");
  const std::string m = message_of(nested(66));
  EXPECT_NE(m.find("t.json: malformed JSON: nested deeper than 64 levels"), std::string::npos) << m;
  EXPECT_NE(message_of("{\"a\": " + nested(65) + "}").find("nested deeper"), std::string::npos);
}

TEST(JsonText, MalformedTextIsAnInputErrorWithItsByte) {
  EXPECT_NE(message_of("{} x").find("malformed JSON at byte"), std::string::npos);  // strict: nothing after
  EXPECT_NE(message_of("").find("malformed JSON"), std::string::npos);
  EXPECT_NE(message_of("[1, 2").find("malformed JSON"), std::string::npos);
  EXPECT_NE(message_of("[1e999]").find("malformed JSON"), std::string::npos);
}

// The document is nlohmann's: the same values as json::parse on a model of the repository and on
// an array of many objects (the shape that a parse callback made quadratic).
TEST(JsonText, SameDocumentAsNlohmannsParser) {
  const std::string text = beamfea::test::read_text(beamfea::test::source_path("examples/01_space_frame/model.json"));
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(parse_json_text(text, "m"), json::parse(text));

  std::string many = "[";
  for (int i = 0; i < 20000; ++i) {
    if (i > 0) many += ',';
    many += "{\"id\": ";
    many += std::to_string(i);
    many += ", \"xyz\": [1.5, -2, 3e-7]}";
  }
  many += "]";
  const json doc = parse_json_text(many, "many");
  EXPECT_EQ(doc, json::parse(many));
  EXPECT_EQ(doc.size(), 20000u);
}

}  // namespace json_text_test

// write_results_json (io/json_writer.hpp): the text of results.json. What it must keep: every value
// reads back exactly (numbers to the last bit: std::to_chars gives the shortest round-trip text,
// C++17 [utility.to.chars]), objects indented as dump(2), arrays of scalars on one line.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/json_writer.hpp"

namespace json_writer_test {

using namespace beamfea;
using ojson = nlohmann::ordered_json;

namespace {
std::string text_of(const ojson& v) {
  std::string s;
  write_results_json(v, s);
  return s;
}
}  // namespace

TEST(JsonWriter, LayoutObjectsIndentedScalarArraysOnOneLine) {
  ojson v = ojson::object();
  v["a"] = {1.0, -2.5e-07, 0.0};
  v["b"] = ojson::object();
  v["c"] = ojson::array();
  v["d"] = {{{"x", 1}}, {1, 2}};
  v["s"] = "ok";
  EXPECT_EQ(text_of(v),
            "{\n"
            "  \"a\": [1.0, -2.5e-07, 0.0],\n"
            "  \"b\": {},\n"
            "  \"c\": [],\n"
            "  \"d\": [\n"
            "    {\n"
            "      \"x\": 1\n"
            "    },\n"
            "    [1, 2]\n"
            "  ],\n"
            "  \"s\": \"ok\"\n"
            "}");
}

TEST(JsonWriter, NumbersReadBackBitForBitAndStayFloatingPoint) {
  const double values[] = {0.1, 1.0 / 3.0, -17251.231662345606, 1e-300, 4.9e-324, 1.7976931348623157e308,
                           1e21, 123456789012345680.0, -0.0, 3.0, 2.0 / 7.0 * 1e-12};
  ojson a = ojson::array();
  for (const double x : values) a.push_back(x);
  a.push_back(std::int64_t{-42});
  a.push_back(std::uint64_t{18446744073709551615u});
  const ojson back = ojson::parse(text_of(a));
  ASSERT_EQ(back.size(), a.size());
  for (std::size_t i = 0; i < std::size(values); ++i) {
    ASSERT_TRUE(back[i].is_number_float()) << i << ": " << back[i].dump();
    const double x = back[i].get<double>();
    EXPECT_EQ(std::memcmp(&x, &values[i], sizeof x), 0) << i << ": " << values[i] << " read back as " << x;
  }
  EXPECT_EQ(back[std::size(values)].get<std::int64_t>(), -42);
  EXPECT_EQ(back[std::size(values) + 1].get<std::uint64_t>(), 18446744073709551615u);
  EXPECT_EQ(text_of(ojson(3.0)), "3.0");
}

// The writer remembers the text of recent numbers (io/json_writer.cpp, write_double): a repeated
// value, the same value negated, two values sharing a slot in turn, and the longest texts must
// come out exactly as std::to_chars writes each one afresh (plus ".0" where it wrote an integer).
TEST(JsonWriter, RememberedNumbersAreWrittenAsIfFormattedAfresh) {
  std::vector<double> values = {0.0, -0.0, 0.0, 1e21, -1e21, 1234567890123456800000.0, -1234567890123456800000.0,
                                2.2250738585072014e-308, -2.2250738585072014e-308, 4.9e-324, 1.7976931348623157e308,
                                -17251.231662345606, 17251.231662345606, -17251.231662345606, 3.0, -3.0, 3.0};
  for (int i = 0; i < 3000; ++i) {  // about 12 values per slot of the 256: each slot taken over many times
    const double v = (i % 7 - 3) * 1234.5678 / (i + 1);
    values.insert(values.end(), {v, -v, v, std::ldexp(v, i % 40)});
  }
  ojson a = ojson::array();
  std::string expected = "[";
  for (const double x : values) {
    a.push_back(x);
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    std::string t(buf, r.ptr);
    if (t.find_first_of(".e") == std::string::npos) t += ".0";
    expected += (expected.size() > 1 ? ", " : "") + t;
  }
  expected += "]";
  EXPECT_EQ(text_of(a), expected);
  EXPECT_EQ(text_of(a), expected);  // the second time from a table full of the first's texts
}

TEST(JsonWriter, NonFiniteNumbersAreNullAsNlohmannWritesThem) {
  ojson a = {std::numeric_limits<double>::infinity(), std::nan(""), 1.5};
  EXPECT_EQ(text_of(a), "[null, null, 1.5]");
}

TEST(JsonWriter, StringsEscapedAndUtf8PassedThrough) {
  ojson v = ojson::object();
  v["quote\"back\\slash"] = "tab\there\nnew\x01line";
  v["utf8"] = "\xce\xbb = 1.5 \xe2\x80\x94 ok";
  const std::string t = text_of(v);
  EXPECT_NE(t.find("\"quote\\\"back\\\\slash\": \"tab\\there\\nnew\\u0001line\""), std::string::npos) << t;
  EXPECT_EQ(ojson::parse(t), v);
}

TEST(JsonWriter, ANestedResultReadsBackEqual) {
  ojson r = ojson::parse(R"({"analyses": {"lin": {"type": "linear_static", "status": "ok",
      "nodes": {"A": {"displacement": [0.0, -1.25e-3, 0.0, 0.0, 0.0, -0.001875], "reaction": null}},
      "elements": {"e": {"stations": [{"x": 0.0, "forces": [1, 2, 3, 4, 5, 6]}, {"x": 0.5, "forces": []}]}},
      "stable": true, "modes": [[1.0, 2.0], [3.0]]}}})");
  EXPECT_EQ(ojson::parse(text_of(r)), r);
}

TEST(JsonWriter, TheStreamedFileIsTheTextAndANewlineAcrossManyChunks) {
  // Several megabytes: the file writer hands its buffer to the stream about every megabyte.
  ojson r = {{"elements", ojson::array()}};
  for (int i = 0; i < 16000; ++i)
    r["elements"].push_back({{"id", i}, {"forces", {i * 0.1, -i / 3.0, 1e-9 * i, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 1.0 / (i + 1)}}});
  std::string text;
  write_results_json(r, text);
  ASSERT_GT(text.size(), std::size_t{2} << 20);
  const auto path = std::filesystem::temp_directory_path() / ("json_writer_test_" + std::to_string(::getpid()) + ".json");
  write_results_json_file(r, path);
  std::ifstream in(path, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(path);
  EXPECT_EQ(file, text + "\n");
  EXPECT_EQ(ojson::parse(file), r);
}

TEST(JsonWriter, AFileThatCannotBeWrittenIsAnErrorAndLeavesNothing) {
  const auto dir = std::filesystem::temp_directory_path() / ("json_writer_missing_" + std::to_string(::getpid()));
  EXPECT_THROW(write_results_json_file(ojson{{"a", 1}}, dir / "results.json"), Error);
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace json_writer_test

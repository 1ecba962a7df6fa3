// write_results_json (io/json_writer.hpp): the text of results.json. What it must keep: every value
// reads back exactly (numbers to the last bit: std::to_chars gives the shortest round-trip text,
// C++17 [utility.to.chars]), objects indented as dump(2), arrays of scalars on one line; with a
// ParallelTasks hook, byte for byte the text written on one thread, and no file when a task fails.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>
#include <unistd.h>

#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/json_writer.hpp"
#include "support/files.hpp"
#include "support/parallel_hooks.hpp"

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

namespace {

using beamfea::test::last_first;
using beamfea::test::ThreadPerTask;

// prefix + i, built by appending (GCC 12 warns falsely, -Wrestrict, on "literal" + std::string
// inlined here: its bug 105329).
std::string named(const char* prefix, int i, const char* suffix = "") {
  std::string s = prefix;
  s += std::to_string(i);
  s += suffix;
  return s;
}

// A results tree of the shape of a large model's, with what the writer must render exactly in
// every slice: 20,000 nodes of two 6-double arrays (some non-finite: null), integers, strings to
// escape (and UTF-8), small nested objects, an array of arrays, a flat array of 5,000 numbers (one
// line: never sliced), and a big object nested inside a big array's member (written serially
// inside its slice). `bad_utf8_at` >= 0: that node's tag is invalid UTF-8 (nlohmann then throws).
ojson large_results(int bad_utf8_at = -1) {
  ojson nodes = ojson::object();
  for (int i = 0; i < 20000; ++i) {
    const double a = 1.0 / (i + 3), b = -i * 1.25e-5;
    ojson n = ojson::object();
    n["displacement"] = {a, b, a * b, 0.0, -0.0, 1e-300 * i};
    n["reaction"] = {i % 997 == 0 ? std::numeric_limits<double>::infinity() : 3.0 * i, std::nan(""), -a, 1e21, b, 2.5};
    if (i % 7 == 0) n["tag"] = named("node \"", i, "\"\t\x01 \xce\xbb");
    if (i == bad_utf8_at) n["tag"] = "bad \xff byte";
    if (i % 5 == 0) n["support"] = {{"fixed", ojson::array({true, false, true})}, {"count", -i}, {"none", nullptr}};
    nodes[named("n", i)] = std::move(n);
  }
  ojson steps = ojson::array();
  for (int k = 0; k < 1500; ++k) {
    ojson step = {{"k", k}, {"lambda", k / 7.0}};
    if (k == 700) {
      ojson inner = ojson::object();
      for (int j = 0; j < 3000; ++j) inner[named("j", j)] = {{"u", j * 0.5}};
      step["nodes"] = std::move(inner);
    }
    steps.push_back(std::move(step));
  }
  ojson modes = ojson::array();
  for (int k = 0; k < 2000; ++k) modes.push_back({k * 0.1, -k / 3.0, std::uint64_t{18446744073709551615u}});
  ojson flat = ojson::array();
  for (int k = 0; k < 5000; ++k) flat.push_back(k / 9.0);
  ojson lin = {{"type", "linear_static"}, {"status", "ok"}, {"nodes", std::move(nodes)}, {"steps", std::move(steps)},
               {"modes", std::move(modes)}, {"flat", std::move(flat)}, {"empty", ojson::object()}, {"none", ojson::array()}};
  return {{"beamfea", "0.1.0"}, {"analyses", {{"lin", std::move(lin)}}}};
}

std::filesystem::path temp_file(const std::string& stem) {
  return std::filesystem::temp_directory_path() / (stem + "_" + std::to_string(::getpid()) + ".json");
}

}  // namespace

TEST(JsonWriter, ALargeResultOnThreadsIsByteForByteTheSerialText) {
  const ojson r = large_results();
  const std::string serial = text_of(r);
  ASSERT_GT(serial.size(), std::size_t{3} << 20);
  const ThreadPerTask threads;
  std::string threaded;
  write_results_json(r, threaded, threads);
  EXPECT_GT(*threads.calls, std::size_t{2});  // the big members went through the hook
  EXPECT_TRUE(threaded == serial);            // (not EXPECT_EQ: a failure would print megabytes)
  std::string reversed;
  write_results_json(r, reversed, last_first);
  EXPECT_TRUE(reversed == serial);
  const ojson back = ojson::parse(serial);
  EXPECT_TRUE(back["analyses"]["lin"]["nodes"]["n997"]["reaction"][0].is_null());
  EXPECT_EQ(back["analyses"]["lin"]["nodes"]["n7"]["tag"], r["analyses"]["lin"]["nodes"]["n7"]["tag"]);
  EXPECT_EQ(back["analyses"]["lin"]["steps"], r["analyses"]["lin"]["steps"]);

  const auto path = temp_file("json_writer_threads");
  write_results_json_file(r, path, threads);
  const std::string file = beamfea::test::read_text(path);
  std::filesystem::remove(path);
  EXPECT_TRUE(file == serial + "\n");
}

TEST(JsonWriter, ASmallResultCallsNoTasks) {
  // Example-sized results (tens of nodes) are written on the calling thread: no threads started.
  ojson r = large_results();
  auto& nodes = r["analyses"]["lin"]["nodes"];
  nodes.erase(std::next(nodes.begin(), 50), nodes.end());
  r["analyses"]["lin"].erase("steps");
  r["analyses"]["lin"].erase("modes");
  const ThreadPerTask threads;
  std::string threaded;
  write_results_json(r, threaded, threads);
  EXPECT_EQ(*threads.calls, std::size_t{0});
  EXPECT_EQ(threaded, text_of(r));
}

TEST(JsonWriter, ATaskThatThrowsIsAnErrorAndLeavesNoFile) {
  // Node 12,345's tag is invalid UTF-8: nlohmann's serialiser throws inside a task (as it does on
  // one thread); the exception reaches the caller and the atomic write leaves nothing.
  const ojson r = large_results(12345);
  const auto dir = std::filesystem::temp_directory_path() / ("json_writer_throws_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const ThreadPerTask threads;
  EXPECT_THROW(write_results_json_file(r, dir / "results.json", threads), nlohmann::json::type_error);
  EXPECT_THROW(write_results_json_file(r, dir / "results.json"), nlohmann::json::type_error);
  // A hook that fails by itself (no thread to be had) after running some windows.
  const ParallelTasks failing = [calls = std::make_shared<int>(0)](std::size_t count, const std::function<void(std::size_t)>& task) {
    if (++*calls == 3) throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again));
    for (std::size_t i = 0; i < count; ++i) task(i);
  };
  EXPECT_THROW(write_results_json_file(large_results(), dir / "results.json", failing), std::system_error);
  EXPECT_TRUE(std::filesystem::is_empty(dir));  // neither results.json nor a temporary
  std::filesystem::remove_all(dir);
}

}  // namespace json_writer_test

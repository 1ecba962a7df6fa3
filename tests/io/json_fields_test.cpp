// json_in::Fields (io/json_util.hpp), the one-pass reading of an object's fields, must be
// expect_keys followed by json_in::require / json_in::field, error for error and value for value:
// the model readers use it for speed, not for other behaviour. Also the results
// helpers made cheaper with it: first_non_finite's walk and set_numbers written over old values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/json_util.hpp"
#include "support/errors.hpp"

namespace beamfea::json_in::json_fields_test {
namespace {

// The InputError `f` throws, as "pointer | message" ("" when it throws none).
template <class F>
std::string error_of(F&& f) {
  const auto e = beamfea::test::thrown<InputError>(std::forward<F>(f));
  return e ? e->pointer() + " | " + e->what() : "";
}

TEST(JsonFields, FindsTheKnownFieldsAndSkipsTheFreeOnes) {
  const json o = json::parse(R"({"xyz": [1, 2, 3], "id": "n1", "_note": 1, "comment": "c", "commenT": 2})");
  const Pointer p("/nodes/4");
  // "commenT" is not the free "comment": the one unknown key.
  EXPECT_EQ(error_of([&] { Fields(o, p, {"id", "xyz"}); }), error_of([&] { expect_keys(o, p, {"id", "xyz"}); }));
  EXPECT_EQ(error_of([&] { expect_keys(o, p, {"id", "xyz"}); }),
            "/nodes/4/commenT | /nodes/4/commenT: unknown key 'commenT' (known keys: id xyz; keys starting with '_' "
            "and \"comment\" are free)");
  const json ok = json::parse(R"({"xyz": [1, 2, 3], "id": "n1", "_note": 1, "comment": "c"})");
  const Fields f(ok, p, {"id", "xyz", "orientation"});
  EXPECT_EQ(f.get("id"), &ok["id"]);
  EXPECT_EQ(f.get("xyz"), &ok["xyz"]);
  EXPECT_EQ(&f.require("xyz", "node"), &ok["xyz"]);
  EXPECT_EQ(f.get("orientation"), nullptr);
  EXPECT_EQ(f.get("comment"), nullptr);  // free keys are not fields
  EXPECT_EQ(f.get("x"), nullptr);        // a prefix of a key is not the key
}

TEST(JsonFields, ErrorsAreThoseOfExpectKeysAndRequire) {
  const Pointer p("/elements/2");
  for (const char* text : {R"({"id": "e", "tpye": "beam"})", R"({"id": "e", "nodez": []})", R"({"Material": "s"})",
                           R"({"id": "e", "zzzzzzzz": 1})", R"({"id": "e"})", R"([1, 2])", R"("e")", R"({})"}) {
    SCOPED_TRACE(text);
    const json o = json::parse(text);
    const std::initializer_list<std::string_view> known = {"id", "type", "nodes", "material"};
    const auto keys = [&] { expect_keys(o, p, {"id", "type", "nodes", "material"}); };
    // The unknown key first, in the object's key order, as expect_keys reports it.
    const std::string unknown = error_of(keys);
    EXPECT_EQ(error_of([&] { Fields(o, p, {"id", "type", "nodes", "material"}); }), unknown);
    if (!unknown.empty()) continue;
    const Fields f(o, p, known);
    for (const char* key : {"id", "type"}) {
      const std::string fresh = error_of([&] { (void)require(o, p, key, "element 'e'"); });
      EXPECT_EQ(error_of([&] { (void)f.require(key, "element 'e'"); }), fresh);
      EXPECT_EQ(f.get(key) != nullptr, fresh.empty());
    }
  }
  // The messages themselves (the readers' tests check them through whole models too).
  const json o = json::parse(R"({"id": "e"})");
  EXPECT_EQ(error_of([&] { (void)Fields(o, p, {"id", "type"}).require("type", "element 'e'"); }),
            "/elements/2/type | /elements/2/type: element 'e': missing field 'type'");
  const json a = json::array();
  EXPECT_EQ(error_of([&] { (void)Fields(a, p, {"id"}).require("id", "element"); }),
            "/elements/2 | /elements/2: element: expected an object");
}

TEST(JsonFields, AKeyReadButNotKnownIsAProgrammingError) {
  const json o = json::parse(R"({"id": "e", "comment": "free"})");
  const Pointer p("/elements/0");
  const Fields f(o, p, {"id", "type"});
  EXPECT_THROW((void)f.require("type", "element"), InputError);  // known but absent: the user's error
  // A key the reader did not list (here a free one, present) is the reader's mistake.
  EXPECT_THROW((void)f.require("comment", "element"), std::logic_error);
  const std::initializer_list<std::string_view> many = {"a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k",
                                                        "l", "m", "n", "o", "p", "q", "r", "s", "t", "u", "v",
                                                        "w", "x", "y", "z", "A", "B", "C", "D", "E", "F", "G"};
  ASSERT_GT(many.size(), Fields::kMaxKnown);
  EXPECT_THROW((void)Fields(o, p, many), std::logic_error);
}

TEST(ResultsHelpers, FirstNonFiniteNamesTheFirstNonFiniteNumberAtAnyDepth) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  ojson r = ojson::parse(R"({"type": "stiffness", "rank": 6, "m": [[1.0, 2.0], [3.0, 4.0]], "o": {"v": [1.5], "s": "x"}})");
  EXPECT_EQ(first_non_finite(r), "");
  r["o"]["v"][0] = inf;
  EXPECT_EQ(first_non_finite(r), "o.v[0]");
  r["m"][1][0] = nan;  // earlier in key order
  EXPECT_EQ(first_non_finite(r), "m[1][0]");
  EXPECT_EQ(first_non_finite(ojson(nan)), "(value)");
  EXPECT_EQ(first_non_finite(ojson::array({1.0, ojson::array({ojson::array({-inf})})})), "[1][0][0]");
}

TEST(ResultsHelpers, NumbersWrittenOverAnyOldValueAreTheFreshArray) {
  const double x[6] = {1.0, -2.5, 3e-300, 0.0, 7.0, -0.0};
  for (const char* old : {R"(null)", R"("s")", R"([])", R"([9.0, "a", null, [1], 4, 5.5, 6.0, 7.0])", R"([1.0, 2.0])",
                          R"({"a": 1})"}) {
    for (std::size_t n : {0u, 2u, 6u}) {
      SCOPED_TRACE(std::string(old) + " n=" + std::to_string(n));
      ojson v = ojson::parse(old);
      set_numbers(v, x, n);
      ojson fresh = ojson::array();
      for (std::size_t i = 0; i < n; ++i) fresh.push_back(x[i]);
      EXPECT_EQ(v, fresh);
      for (std::size_t i = 0; i < n; ++i) EXPECT_TRUE(v[i].is_number_float());
      EXPECT_EQ(v.dump(), fresh.dump());  // -0.0 and 3e-300 kept as written
    }
  }
}

}  // namespace
}  // namespace beamfea::json_in::json_fields_test

// A model read again and again into one ModelBuffer, and results written again and again into one
// RunReport (a sweep worker's case after case), are the fresh read's and the fresh
// run's, bit for bit: over every document of the fuzz corpus (tests/fuzz/corpus: models of each
// analysis type and shape, and bad input of many kinds), read forward and then backward so that
// each collection grows and shrinks, with bad documents in between.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "support/files.hpp"
#include "support/models.hpp"

namespace reused_storage_test {

using namespace beamfea;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// The parsed documents of the fuzz corpus, by file name (malformed JSON left out: it never
// reaches a reader).
std::vector<std::pair<std::string, json>> corpus() {
  std::vector<std::pair<std::string, json>> docs;
  for (const auto& f : test::files_in(test::source_path("tests/fuzz/corpus"), ".json")) {
    try {
      docs.emplace_back(f.filename().string(), read_json_file(f.string()));
    } catch (const InputError&) {
    }
  }
  return docs;
}

// The corpus forward, then backward: every document follows a larger and a smaller one.
std::vector<std::size_t> there_and_back(std::size_t n) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < n; ++i) order.push_back(i);
  for (std::size_t i = n; i-- > 0;) order.push_back(i);
  return order;
}

// memcmp's pointers must not be null even for n = 0 (an empty vector's data() may be).
bool same_bits(const double* a, const double* b, std::size_t n) {
  return n == 0 || std::memcmp(a, b, n * sizeof(double)) == 0;
}
bool same_bits(const Vec3& a, const Vec3& b) { return same_bits(a.data(), b.data(), 3); }
bool same_bits(const Mat3& a, const Mat3& b) { return same_bits(a.data(), b.data(), 9); }
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && same_bits(a.data(), b.data(), a.size());
}
bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && same_bits(a.data(), b.data(), static_cast<std::size_t>(a.size()));
}

void expect_same_loads(const LoadSet& a, const LoadSet& b, const std::string& where) {
  ASSERT_EQ(a.nodal.size(), b.nodal.size()) << where;
  for (std::size_t i = 0; i < a.nodal.size(); ++i)
    EXPECT_TRUE(a.nodal[i].node == b.nodal[i].node && same_bits(a.nodal[i].force, b.nodal[i].force) &&
                same_bits(a.nodal[i].moment, b.nodal[i].moment))
        << where << " nodal load " << i;
  ASSERT_EQ(a.joint.size(), b.joint.size()) << where;
  for (std::size_t i = 0; i < a.joint.size(); ++i)
    EXPECT_TRUE(a.joint[i].joint == b.joint[i].joint && a.joint[i].coordinate == b.joint[i].coordinate &&
                same_bits(&a.joint[i].value, &b.joint[i].value, 1))
        << where << " joint load " << i;
  ASSERT_EQ(a.member.size(), b.member.size()) << where;
  for (std::size_t i = 0; i < a.member.size(); ++i) {
    const MemberLoad &x = a.member[i], &y = b.member[i];
    EXPECT_TRUE(x.member == y.member && x.kind == y.kind && x.local == y.local && same_bits(x.q_from, y.q_from) &&
                same_bits(x.q_to, y.q_to) && same_bits(&x.from, &y.from, 1) && same_bits(&x.to, &y.to, 1) &&
                same_bits(x.force, y.force) && same_bits(x.moment, y.moment) && same_bits(&x.at, &y.at, 1))
        << where << " member load " << i;
  }
  EXPECT_TRUE(same_bits(a.gravity, b.gravity)) << where;
}

// Every field of the two models, doubles compared bit for bit; and every id found where a fresh
// model finds it.
void expect_same_model(const Model& a, const Model& b, const std::string& where) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size()) << where;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_TRUE(a.nodes[i].id == b.nodes[i].id && same_bits(a.nodes[i].x, b.nodes[i].x) && a.nodes[i].member == b.nodes[i].member)
        << where << " node " << i;
    EXPECT_EQ(a.find_node(b.nodes[i].id), b.find_node(b.nodes[i].id)) << where;
  }
  ASSERT_EQ(a.materials.size(), b.materials.size()) << where;
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    const Material &x = a.materials[i], &y = b.materials[i];
    EXPECT_TRUE(x.id == y.id && same_bits(&x.E, &y.E, 1) && same_bits(&x.G, &y.G, 1) && same_bits(&x.density, &y.density, 1))
        << where << " material " << i;
    EXPECT_EQ(a.find_material(y.id), static_cast<int>(i)) << where;
  }
  ASSERT_EQ(a.sections.size(), b.sections.size()) << where;
  for (std::size_t i = 0; i < a.sections.size(); ++i) {
    const Section &x = a.sections[i], &y = b.sections[i];
    const double xs[] = {x.A, x.Iy, x.Iz, x.J, x.ky, x.kz}, ys[] = {y.A, y.Iy, y.Iz, y.J, y.ky, y.kz};
    EXPECT_TRUE(x.id == y.id && same_bits(xs, ys, 6)) << where << " section " << i;
    EXPECT_EQ(a.find_section(y.id), static_cast<int>(i)) << where;
  }
  ASSERT_EQ(a.members.size(), b.members.size()) << where;
  for (std::size_t i = 0; i < a.members.size(); ++i) {
    const Member &x = a.members[i], &y = b.members[i];
    EXPECT_TRUE(x.id == y.id && x.type == y.type && x.nodes == y.nodes && x.material == y.material && x.section == y.section &&
                same_bits(x.orientation, y.orientation) && x.theory == y.theory && x.divisions == y.divisions &&
                x.elements == y.elements)
        << where << " member " << i;
    EXPECT_EQ(a.find_member(y.id), static_cast<int>(i)) << where;
  }
  ASSERT_EQ(a.elements.size(), b.elements.size()) << where;
  for (std::size_t i = 0; i < a.elements.size(); ++i) {
    const Element &x = a.elements[i], &y = b.elements[i];
    EXPECT_TRUE(x.id == y.id && x.type == y.type && x.nodes == y.nodes && x.material == y.material && x.section == y.section &&
                same_bits(x.orientation, y.orientation) && x.theory == y.theory && x.member == y.member)
        << where << " element " << i;
  }
  ASSERT_EQ(a.joints.size(), b.joints.size()) << where;
  for (std::size_t i = 0; i < a.joints.size(); ++i) {
    const Joint &x = a.joints[i], &y = b.joints[i];
    bool axes = x.axes.size() == y.axes.size();
    for (std::size_t k = 0; axes && k < x.axes.size(); ++k) axes = same_bits(x.axes[k], y.axes[k]);
    EXPECT_TRUE(x.id == y.id && x.type == y.type && x.nodes == y.nodes && axes && x.translations == y.translations &&
                same_bits(x.stiffness, y.stiffness) && same_bits(x.stiffness_matrix, y.stiffness_matrix))
        << where << " joint " << i;
    EXPECT_EQ(a.find_joint(y.id), static_cast<int>(i)) << where;
  }
  ASSERT_EQ(a.supports.size(), b.supports.size()) << where;
  for (std::size_t i = 0; i < a.supports.size(); ++i)
    EXPECT_TRUE(a.supports[i].node == b.supports[i].node && a.supports[i].fixed == b.supports[i].fixed) << where;
  ASSERT_EQ(a.prescribed.size(), b.prescribed.size()) << where;
  for (std::size_t i = 0; i < a.prescribed.size(); ++i)
    EXPECT_TRUE(a.prescribed[i].dof == b.prescribed[i].dof && same_bits(&a.prescribed[i].value, &b.prescribed[i].value, 1))
        << where;
  expect_same_loads(a.default_loads(), b.default_loads(), where + " default loads");
  ASSERT_EQ(a.masses.size(), b.masses.size()) << where;
  for (std::size_t i = 0; i < a.masses.size(); ++i)
    EXPECT_TRUE(a.masses[i].node == b.masses[i].node && same_bits(&a.masses[i].mass, &b.masses[i].mass, 1) &&
                same_bits(a.masses[i].inertia, b.masses[i].inertia))
        << where << " mass " << i;
  ASSERT_EQ(a.load_cases.size(), b.load_cases.size()) << where;
  for (std::size_t i = 0; i < a.load_cases.size(); ++i) {
    EXPECT_EQ(a.load_cases[i].id, b.load_cases[i].id) << where;
    expect_same_loads(a.load_cases[i].loads, b.load_cases[i].loads, where + " load case " + b.load_cases[i].id);
  }
  ASSERT_EQ(a.combinations.size(), b.combinations.size()) << where;
  for (std::size_t i = 0; i < a.combinations.size(); ++i)
    EXPECT_TRUE(a.combinations[i].id == b.combinations[i].id && a.combinations[i].factors == b.combinations[i].factors) << where;
  EXPECT_EQ(a.find_node("no such id"), -1) << where;
}

// The message of the InputError or ModelError that `f` throws ("" when none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return std::string("InputError at ") + e.pointer() + ": " + e.what();
  } catch (const ModelError& e) {
    return std::string("ModelError: ") + e.what();
  }
  return "";
}

// results.json's text without the wall times (which differ from run to run). ordered_json's
// dump writes each double so that it reads back to the same bits.
std::string text_without_wall_times(ojson v) {
  struct Strip {
    static void in(ojson& x) {
      if (x.is_object()) {
        x.erase("wall_time_s");
        for (auto& [k, y] : x.items()) in(y);
      } else if (x.is_array()) {
        for (auto& y : x) in(y);
      }
    }
  };
  Strip::in(v);
  return v.dump();
}

}  // namespace

TEST(ModelBuffer, ReadsEachDocumentOfTheCorpusAsAFreshRead) {
  const auto docs = corpus();
  ASSERT_GT(docs.size(), 30u);
  ModelBuffer buffer;
  std::size_t read = 0, refused = 0;
  for (const std::size_t i : there_and_back(docs.size())) {
    const auto& [name, doc] = docs[i];
    Model fresh;
    const std::string fresh_error = error_of([&] { fresh = read_model(doc); });
    const std::string reused_error = error_of([&] { buffer.read(doc); });
    EXPECT_EQ(reused_error, fresh_error) << name;
    if (!fresh_error.empty() || !reused_error.empty()) {
      ++refused;
      continue;
    }
    ++read;
    expect_same_model(buffer.model(), fresh, name);
  }
  // Both kinds, many times each (the corpus holds seeds of every analysis and bad input).
  EXPECT_GT(read, 40u);
  EXPECT_GT(refused, 8u);
}

TEST(ModelBuffer, ReadingADocumentOfTheSameShapeAgainTakesNoNewStorage) {
  // Two reads ago's storage comes back (the buffer keeps two models and swaps them): the vectors
  // and the joints' axes sit where they sat, so nothing was allocated for them.
  const json doc = test::cantilever(2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6, 4);
  ModelBuffer buffer;
  buffer.read(doc);
  buffer.read(doc);
  const Node* nodes = buffer.read(doc).nodes.data();
  const Element* elements = buffer.model().elements.data();
  const std::size_t node_count = buffer.model().nodes.size();
  buffer.read(doc);
  const Model& again = buffer.read(doc);
  EXPECT_EQ(again.nodes.data(), nodes);
  EXPECT_EQ(again.elements.data(), elements);
  EXPECT_EQ(again.nodes.size(), node_count);
  EXPECT_EQ(node_count, 5u);  // A, B and the three internal nodes of four divisions
}

TEST(RunDocument, AReusedReportGivesEachDocumentTheFreshReport) {
  const auto docs = corpus();
  ModelBuffer buffer;
  RunReport reused;
  std::size_t ran = 0, failed = 0;
  for (const std::size_t i : there_and_back(docs.size())) {
    const auto& [name, doc] = docs[i];
    std::optional<Model> fresh_model;
    if (!error_of([&] { fresh_model.emplace(load_and_check(doc)); }).empty()) continue;
    const Model& model = load_and_check(doc, buffer);
    RunReport fresh;
    const std::string fresh_error = error_of([&] { fresh = run_document(*fresh_model, doc, {}); });
    const std::string reused_error = error_of([&] { run_document(model, doc, {}, reused); });
    ASSERT_EQ(reused_error, fresh_error) << name;
    if (!fresh_error.empty()) continue;
    ++ran;
    if (fresh.failed) ++failed;
    EXPECT_EQ(text_without_wall_times(reused.results), text_without_wall_times(fresh.results)) << name;
    EXPECT_EQ(reused.failed, fresh.failed) << name;
    ASSERT_EQ(reused.outcomes.size(), fresh.outcomes.size()) << name;
    for (std::size_t k = 0; k < fresh.outcomes.size(); ++k) {
      EXPECT_EQ(reused.outcomes[k].first, fresh.outcomes[k].first) << name;
      EXPECT_EQ(reused.outcomes[k].second.termination, fresh.outcomes[k].second.termination) << name;
      EXPECT_EQ(reused.outcomes[k].second.message, fresh.outcomes[k].second.message) << name;
    }
  }
  // Every analysis type ran, some of them failing (mechanisms, a non-finite result).
  EXPECT_GT(ran, 30u);
  EXPECT_GT(failed, 0u);
}

}  // namespace reused_storage_test

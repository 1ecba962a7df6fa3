// DofMap::rebuild (core/dof_map.hpp): a map rebuilt over another model's map is, bit for bit, the
// map a new DofMap builds. The structure cache of a sweep (solvers/structure_cache.hpp) rebuilds
// its map case after case over the last one's storage, so a value left over from an earlier model
// (a loop row, a dependent DOF, a redundant constraint, a prescribed value) would be a wrong result.
// The models are the loop tests' closed loops (closure rows, supports on slaves, redundant rows)
// and examples/03's open chain, rebuilt in one order and then in the reverse order.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/dof_map.hpp"
#include "io/model_reader.hpp"
#include "solvers/loop_models.hpp"  // tests/solvers: the loop tests' models

namespace dof_map_rebuild_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {

void expect_same_matrix(const SparseRowMatrix& a, const SparseRowMatrix& b, const char* what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  ASSERT_EQ(a.nonZeros(), b.nonZeros()) << what;
  for (Eigen::Index r = 0; r < a.outerSize(); ++r) {
    SparseRowMatrix::InnerIterator x(a, r), y(b, r);
    for (; x && y; ++x, ++y) {
      EXPECT_EQ(x.col(), y.col()) << what << " row " << r;
      EXPECT_EQ(x.value(), y.value()) << what << " row " << r;  // bitwise: the same sums
    }
    EXPECT_FALSE(x || y) << what << " row " << r << ": a different number of entries";
  }
}

void expect_same_edges(const std::vector<ConstraintEdge>& a, const std::vector<ConstraintEdge>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].kind, b[i].kind);
    EXPECT_EQ(a[i].index, b[i].index);
    EXPECT_EQ(a[i].parent, b[i].parent);
    EXPECT_EQ(a[i].child, b[i].child);
    EXPECT_EQ(a[i].forward, b[i].forward);
  }
}

// Everything a caller reads of a map, compared between the rebuilt one and a new one.
void expect_same_map(const DofMap& rebuilt, const DofMap& fresh) {
  ASSERT_EQ(rebuilt.raw_size(), fresh.raw_size());
  ASSERT_EQ(rebuilt.free_size(), fresh.free_size());
  ASSERT_EQ(rebuilt.prescribed_size(), fresh.prescribed_size());
  expect_same_matrix(rebuilt.T_free(), fresh.T_free(), "T_free");
  expect_same_matrix(rebuilt.T_prescribed(), fresh.T_prescribed(), "T_prescribed");
  EXPECT_EQ(rebuilt.free_dofs(), fresh.free_dofs());
  for (int p = 0; p < fresh.prescribed_size(); ++p) {
    EXPECT_EQ(rebuilt.prescribed()[p].dof, fresh.prescribed()[p].dof);
    EXPECT_EQ(rebuilt.prescribed()[p].value, fresh.prescribed()[p].value);
    EXPECT_EQ(rebuilt.prescribed()[p].support, fresh.prescribed()[p].support);
  }
  for (int r = 0; r < fresh.raw_size(); ++r) {
    EXPECT_EQ(rebuilt.free_index(r), fresh.free_index(r));
    EXPECT_EQ(rebuilt.prescribed_index(r), fresh.prescribed_index(r));
  }
  expect_same_edges(rebuilt.tree_edges(), fresh.tree_edges());
  expect_same_edges(rebuilt.loop_edges(), fresh.loop_edges());
  EXPECT_EQ(rebuilt.tree_order(), fresh.tree_order());
  EXPECT_EQ(rebuilt.redundant_constraints(), fresh.redundant_constraints());

  // The constraint forces read the extra rows over independent DOFs and the multipliers' rows.
  Eigen::VectorXd r(fresh.raw_size());
  for (int i = 0; i < r.size(); ++i) r[i] = std::sin(1.0 + i);
  const DofMap::ConstraintForces a = rebuilt.constraint_forces(r), b = fresh.constraint_forces(r);
  EXPECT_EQ(a.prescribed, b.prescribed);
  ASSERT_EQ(a.joint.size(), b.joint.size());
  for (std::size_t j = 0; j < a.joint.size(); ++j) EXPECT_EQ(a.joint[j], b.joint[j]) << "joint " << j;
  ASSERT_EQ(a.loop.size(), b.loop.size());
  for (std::size_t l = 0; l < a.loop.size(); ++l) EXPECT_EQ(a.loop[l], b.loop[l]) << "loop " << l;
  Eigen::VectorXd up(fresh.prescribed_size());
  for (int i = 0; i < up.size(); ++i) up[i] = 1e-3 * (i + 1);
  EXPECT_EQ(rebuilt.check_consistency(up), fresh.check_consistency(up));
}

}  // namespace

TEST(DofMapRebuild, AMapRebuiltOverAnotherModelsMapIsTheNewMapBitForBit) {
  std::vector<Model> models;
  FourBar turned;
  turned.theta0 = 0.7;  // the same structure in another geometry
  for (bool ground_link : {false, true})
    for (bool released : {false, true}) models.push_back(read_model(four_bar_model(FourBar{}, ground_link, released)));
  models.push_back(read_model(four_bar_model(turned, true, false)));
  for (bool ground_link : {false, true}) models.push_back(read_model(five_bar_model(FiveBar{}, ground_link)));
  for (bool ground_link : {false, true}) models.push_back(read_model(sway_frame_model(3.0, 4.0, 1e3, 1.0, ground_link)));
  models.push_back(read_model(read_json_file(BEAMFEA_SOURCE_DIR "/examples/03_workspace_stiffness_map/model.json")));

  // The models in turn and then back, each over the map of the one before: every model is
  // rebuilt over a larger and over a smaller map than its own.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < models.size(); ++i) order.push_back(i);
  for (std::size_t i = models.size(); i-- > 0;) order.push_back(i);
  DofMap map(models[order[0]]);
  int with_loops = 0, with_redundant = 0;
  for (const std::size_t i : order) {
    SCOPED_TRACE("model " + std::to_string(i));
    map.rebuild(models[i], reference_configuration(models[i]));
    const DofMap fresh(models[i]);
    expect_same_map(map, fresh);
    with_loops += fresh.loop_edges().empty() ? 0 : 1;
    with_redundant += fresh.redundant_constraints().empty() ? 0 : 1;
  }
  // The sequence must go through the elimination: closure rows and redundant rows.
  EXPECT_GT(with_loops, 0);
  EXPECT_GT(with_redundant, 0);
}

}  // namespace dof_map_rebuild_test

// The planned pattern of K_ff (core/assembly.hpp: planned_pattern, SystemAssembler::plan), and the
// linear analysis that orders it while the element matrices are computed
// (solvers/linear_static.cpp, LinearStaticOptions::parallel).
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "io/model_reader.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"
#include "support/files.hpp"
#include "support/models.hpp"
#include "support/parallel_hooks.hpp"

namespace planned_assembly_test {

using namespace beamfea;
using json = nlohmann::json;

namespace {

// A grid frame of (nx+1)(ny+1)(nz+1) nodes fixed at its base, with what changes the map from the
// identity: a rigid link to an offset tip (its DOFs are the arm's), a revolute joint with a spring
// (a released coordinate of its own), a pinned support (prescribed rotations stay free) and a
// prescribed displacement (K_fp).
json frame(int nx, int ny, int nz) {
  json nodes = json::array(), elements = json::array(), supports = json::array(), loads = json::array();
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "n" + std::string inlined here.
  const auto id = [](int i, int j, int k) {
    std::string s = "n";
    s += std::to_string(i);
    s += '_';
    s += std::to_string(j);
    s += '_';
    s += std::to_string(k);
    return s;
  };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        nodes.push_back({{"id", id(i, j, k)}, {"xyz", {4.0 * i, 5.0 * j, 3.0 * k}}});
        if (k == 0) supports.push_back({{"node", id(i, j, k)}, {"fix", (i + j) % 5 == 0 ? json({"ux", "uy", "uz"}) : json("all")}});
        if (k > 0 && (i + j) % 3 == 0) loads.push_back({{"node", id(i, j, k)}, {"force", {1e3 * i, -2e2 * j, -5e3}}});
      }
  int e = 0;
  const auto beam = [&](const std::string& a, const std::string& b) {
    elements.push_back({{"id", "e" + std::to_string(e++)}, {"type", "beam"}, {"nodes", {a, b}}, {"material", "steel"}, {"section", "ipe"}});
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) beam(id(i, j, k), id(i, j, k + 1));
  for (int k = 1; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        if (i < nx) beam(id(i, j, k), id(i + 1, j, k));
        if (j < ny) beam(id(i, j, k), id(i, j + 1, k));
      }
  nodes.push_back({{"id", "arm"}, {"xyz", {0.0, 0.0, 3.0 * nz}}});
  nodes.push_back({{"id", "tip"}, {"xyz", {-1.0, 0.0, 3.0 * nz}}});
  elements.push_back({{"id", "link"}, {"type", "rigid"}, {"nodes", {"arm", "tip"}}});
  loads.push_back({{"node", "tip"}, {"force", {0, 0, -1e3}}});
  json joints = json::array({{{"id", "hinge"}, {"type", "revolute"}, {"nodes", {id(0, 0, nz), "arm"}}, {"axes", {{0, 1, 0}}},
                              {"stiffness", {5e6}}}});
  return {{"nodes", nodes},
          {"materials", {{{"id", "steel"}, {"E", 2.1e11}, {"G", 8.1e10}}}},
          {"sections", {{{"id", "ipe"}, {"A", 5.4e-3}, {"Iy", 8.4e-5}, {"Iz", 6.0e-6}, {"J", 2.0e-7}, {"ky", 1.2}, {"kz", 1.2}}}},
          {"elements", elements},
          {"joints", joints},
          {"supports", supports},
          {"loads", loads},
          {"prescribed", {{{"node", id(nx, ny, nz)}, {"dof", "ux"}, {"value", 1e-3}}}}};
}

struct Assembled {
  SparseMatrix Kff, Kfp;
};

Assembled assemble(const Model& model, const DofMap& map, bool planned) {
  const LinearStructure structure(model);
  SystemAssembler a(map, SystemAssembler::Passes::One);
  if (planned) a.plan(planned_pattern(map, LinearStructure::assembly_blocks(model, map)));
  a.begin();
  structure.assemble(map, a);
  a.end();
  return {a.K_ff(), a.K_fp()};
}

// The planned pattern is the triplets' pattern, entry for entry, and the values agree: bit for bit
// where no entry gathers several terms of one element (no constraint maps two raw DOFs onto one
// free DOF), to rounding where one does (the terms of one element are then added in another order).
void expect_same_assembly(const Model& model, const std::string& name) {
  SCOPED_TRACE(name);
  const DofMap map(model);
  const Assembled triplets = assemble(model, map, false);
  const Assembled planned = assemble(model, map, true);
  ASSERT_EQ(planned.Kff.rows(), triplets.Kff.rows());
  ASSERT_EQ(planned.Kff.nonZeros(), triplets.Kff.nonZeros());
  const Eigen::Index n = triplets.Kff.outerSize();
  EXPECT_TRUE(std::equal(planned.Kff.outerIndexPtr(), planned.Kff.outerIndexPtr() + n + 1, triplets.Kff.outerIndexPtr()));
  EXPECT_TRUE(std::equal(planned.Kff.innerIndexPtr(), planned.Kff.innerIndexPtr() + triplets.Kff.nonZeros(),
                         triplets.Kff.innerIndexPtr()));
  const double scale = triplets.Kff.coeffs().cwiseAbs().maxCoeff();
  EXPECT_LE((planned.Kff.coeffs() - triplets.Kff.coeffs()).cwiseAbs().maxCoeff(), 1e-15 * scale);
  EXPECT_EQ(SparseMatrix(planned.Kfp - triplets.Kfp).norm(), 0.0);
  EXPECT_EQ(planned.Kfp.nonZeros(), triplets.Kfp.nonZeros());
}

}  // namespace

TEST(PlannedAssembly, ThePlannedPatternIsTheTripletsPatternOnEveryKindOfMap) {
  // A frame with a rigid link, a sprung revolute joint, pins and a prescribed displacement.
  expect_same_assembly(test::model_from(frame(3, 2, 2)), "frame");
  // The examples' models: meshed members, the five-bar's closed loop (redundant rows) beam and
  // lumped (rigid links and joint springs only), the robot arm.
  const std::filesystem::path ex = test::source_path("examples");
  for (const char* file : {"01_space_frame/model.json", "03_workspace_stiffness_map/model.json", "04_load_sweep/model.json",
                           "06_lees_frame/model.json", "08_five_bar_lumped_vs_beam/models/beam.json",
                           "08_five_bar_lumped_vs_beam/models/lumped.json", "09_robot_arm_self_weight/model.json"})
    expect_same_assembly(read_model(test::read_json(ex / file)), file);
  for (const auto& file : test::files_in(ex / "05_pashkevich_chain" / "models", ".json"))
    expect_same_assembly(read_model(test::read_json(file)), file.filename().string());
}

TEST(PlannedAssembly, AFrameWithoutConstraintsGetsTheTripletsValuesBitForBit) {
  json doc = frame(3, 3, 2);
  doc["elements"].erase(doc["elements"].size() - 1);  // the rigid link
  doc.erase("joints");
  const Model model = test::model_from(doc);
  const DofMap map(model);
  const Assembled triplets = assemble(model, map, false);
  const Assembled planned = assemble(model, map, true);
  ASSERT_EQ(planned.Kff.nonZeros(), triplets.Kff.nonZeros());
  EXPECT_TRUE(planned.Kff.coeffs().cwiseEqual(triplets.Kff.coeffs()).all());
}

// One process's share of a distributed assembly (SystemAssembler::own, planned_pattern with
// owned columns): three processes splitting the free DOFs into three ranges each assemble K_ff's
// columns and K_fp's rows of their range, every one equal to the whole assembly's, the others
// empty; the three shares add up to the whole K_ff and K_fp. Each process adds the matrices of
// fewer elements than the whole (those that reach its range).
TEST(PlannedAssembly, EachProcessAssemblesItsOwnColumnsAsTheWholeAssemblyHasThem) {
  const Model model = test::model_from(frame(4, 3, 3));
  const DofMap map(model);
  const Assembled whole = assemble(model, map, true);
  const int n = map.free_size();
  ASSERT_GT(map.prescribed_size(), 0);
  const int cut[4] = {0, n / 3, 2 * n / 3, n};
  SparseMatrix sum_ff(n, n), sum_fp(n, map.prescribed_size());
  const LinearStructure structure(model);
  const AssemblyBlocks blocks = LinearStructure::assembly_blocks(model, map);
  for (int p = 0; p < 3; ++p) {
    SCOPED_TRACE(p);
    const OwnedColumns owned{cut[p], cut[p + 1]};
    SystemAssembler a(map, SystemAssembler::Passes::One);
    a.own(owned);
    a.plan(planned_pattern(map, blocks, owned));
    a.begin();
    structure.assemble(map, a);
    a.end();
    const SparseMatrix& K = a.K_ff();
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd mine = K.col(j), all = whole.Kff.col(j);
      if (owned.contains(j)) {
        EXPECT_EQ(K.col(j).nonZeros(), whole.Kff.col(j).nonZeros()) << "column " << j;
        EXPECT_TRUE(mine.cwiseEqual(all).all()) << "column " << j;
      } else {
        EXPECT_EQ(K.col(j).nonZeros(), 0) << "column " << j;
      }
    }
    const Eigen::MatrixXd fp = a.K_fp(), fp_all = whole.Kfp;
    for (int i = 0; i < n; ++i)
      EXPECT_TRUE(fp.row(i).cwiseEqual(owned.contains(i) ? Eigen::RowVectorXd(fp_all.row(i))
                                                         : Eigen::RowVectorXd::Zero(fp.cols())).all()) << "row " << i;
    int reached = 0;
    for (std::size_t b = 0; b < blocks.size(); ++b) reached += a.reaches_owned(blocks.block(b)) ? 1 : 0;
    EXPECT_GT(reached, 0);
    EXPECT_LT(reached, static_cast<int>(blocks.size()));
    sum_ff += K;
    sum_fp += a.K_fp();
  }
  EXPECT_EQ(SparseMatrix(sum_ff - whole.Kff).norm(), 0.0);
  EXPECT_EQ(SparseMatrix(sum_fp - whole.Kfp).norm(), 0.0);
}

TEST(PlannedAssembly, AnEntryOutsideThePlanAndAPlanForManyPassesAreRefused) {
  const Model model = test::model_from(frame(1, 1, 1));
  const DofMap map(model);
  const AssemblyBlocks blocks = LinearStructure::assembly_blocks(model, map);
  ASSERT_GT(blocks.size(), 2u);
  AssemblyBlocks first_only;  // the plan of the first beam alone
  first_only.add(blocks.block(0));
  SystemAssembler a(map, SystemAssembler::Passes::One);
  a.plan(planned_pattern(map, first_only));
  a.begin();
  const LinearStructure structure(model);
  EXPECT_THROW(structure.assemble(map, a), Error);

  SystemAssembler many(map);
  EXPECT_THROW(many.plan(planned_pattern(map, blocks)), Error);
  SystemAssembler wrong_size(map, SystemAssembler::Passes::One);
  EXPECT_THROW(wrong_size.plan(SparseMatrix(3, 3)), Error);
}

TEST(PlannedAssembly, AnAnalysisAheadOfTheValuesIsTheOneFactorizeMakes) {
  // 2,430 free DOFs (CHOLMOD's own orderings) and 20,000 and more (the two orderings of
  // supervariables): factorize after analyze gives what factorize alone gives, bit for bit.
  for (const auto& [nx, nz] : {std::pair{8, 5}, std::pair{23, 7}}) {
    const Model model = test::model_from(frame(nx, nx, nz));
    const DofMap map(model);
    const Assembled K = assemble(model, map, true);
    SCOPED_TRACE(K.Kff.rows());
    SparseFactor alone, ahead;
    ASSERT_EQ(alone.factorize(K.Kff), FactorStatus::Succeeded);
    ahead.analyze(planned_pattern(map, LinearStructure::assembly_blocks(model, map)));
    EXPECT_FALSE(ahead.ordering().empty());
    ASSERT_EQ(ahead.factorize(K.Kff), FactorStatus::Succeeded);
    EXPECT_EQ(ahead.ordering(), alone.ordering());
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.Kff.rows(), -1.0, 2.0);
    EXPECT_TRUE(ahead.solve(b).cwiseEqual(alone.solve(b)).all());
    EXPECT_EQ(ahead.rcond(), alone.rcond());
  }
  // A pattern with an empty column (a DOF without stiffness) is not analysed: factorize reports it.
  SparseMatrix empty_column(400, 400);
  for (int j = 1; j < 400; ++j) empty_column.insert(j, j) = 1.0;
  empty_column.makeCompressed();
  SparseFactor f;
  f.analyze(empty_column);
  EXPECT_TRUE(f.ordering().empty());
  EXPECT_EQ(f.factorize(empty_column), FactorStatus::NotPositiveDefinite);
}

TEST(PlannedAssembly, TheLinearAnalysisOnThreadsEqualsItOnOneBitForBit) {
  // 2,430 free DOFs: above the size from which the tasks go to the hook.
  const Model model = test::model_from(frame(8, 8, 5));
  const LinearStaticResult serial = solve_linear_static(model);
  ASSERT_EQ(serial.status, SolveStatus::Succeeded) << serial.message;
  ASSERT_GT(serial.free_dofs, 2000);
  const test::ThreadPerTask threads;
  for (const ParallelTasks& hook : {ParallelTasks(threads), ParallelTasks(&test::last_first)}) {
    LinearStaticOptions o;
    o.parallel = hook;
    const LinearStaticResult r = solve_linear_static(model, o);
    ASSERT_EQ(r.status, SolveStatus::Succeeded);
    EXPECT_TRUE(r.u.cwiseEqual(serial.u).all());
    ASSERT_EQ(r.end_forces.size(), serial.end_forces.size());
    for (std::size_t e = 0; e < r.end_forces.size(); ++e) EXPECT_TRUE(r.end_forces[e].cwiseEqual(serial.end_forces[e]).all());
    for (std::size_t n = 0; n < r.reactions.size(); ++n) EXPECT_TRUE(r.reactions[n].cwiseEqual(serial.reactions[n]).all());
  }
  EXPECT_EQ(*threads.calls, 1u);
  // Against the closed form that no assembly can fake: the vertical reactions carry the vertical
  // loads (statics), to rounding.
  double fz = 0.0, rz = 0.0;
  for (std::size_t n = 0; n < serial.reactions.size(); ++n) rz += serial.reactions[n][2];
  for (int k = 1; k <= 5; ++k)
    for (int j = 0; j <= 8; ++j)
      for (int i = 0; i <= 8; ++i)
        if ((i + j) % 3 == 0) fz += -5e3;
  fz += -1e3;  // the tip
  EXPECT_NEAR(rz, -fz, 1e-9 * std::abs(fz));
  EXPECT_GT(std::abs(fz), 1e5);
}

TEST(PlannedAssembly, AnElementsErrorOnAThreadIsTheSerialError) {
  // The reader refuses such a beam; a library user's model may still hold one.
  Model model = test::model_from(frame(8, 8, 5));
  model.sections[0].ky = 0.0;
  model.elements[17].theory = BeamTheory::Timoshenko;
  const auto message = [&](const ParallelTasks& hook) {
    LinearStaticOptions o;
    o.parallel = hook;
    try {
      solve_linear_static(model, o);
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string serial = message({});
  EXPECT_NE(serial.find("e17"), std::string::npos) << serial;
  EXPECT_EQ(message(test::ThreadPerTask{}), serial);
}

}  // namespace planned_assembly_test

// The iterative solver (PETSc's conjugate gradients with algebraic multigrid) against the direct
// one on the same models, its computed residual, its failures (not converged, a mechanism) and
// the effect of the rigid-body near null space on multigrid.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/near_null_space.hpp"
#include "solvers/petsc_solver.hpp"
#include "solvers/structure.hpp"
#include "support/files.hpp"
#include "support/models.hpp"

namespace iterative_solver_test {

using namespace beamfea;
using nlohmann::json;

namespace {

// PETSc finalised after the tests, as the program does at exit: what it holds is freed (the
// sanitizer build's leak check sees none of it).
class PetscAtExit : public ::testing::Environment {
 public:
  void TearDown() override { finalize_petsc(); }
};
[[maybe_unused]] ::testing::Environment* const petsc_at_exit = ::testing::AddGlobalTestEnvironment(new PetscAtExit);

constexpr double kRtol = 1e-10;
// Iterative and direct answers differ by up to about cond(K) rtol of the largest displacement;
// the Jacobi-scaled condition numbers of these models stay below 1e5.
constexpr double kAgreement = 1e-5;
// Two computations of one residual (K u against the elements' internal forces) differ by their
// rounding, about eps ||K|| ||u|| / ||F||: up to 1e-13 on these models.
constexpr double kResidualRounding = 1e-12;

// A space frame of nx x ny x nz bays of 1 m (steel rectangular tubes), clamped at z = 0, every top
// node loaded sideways and down.
json cube_frame(int nx, int ny, int nz) {
  json d;
  d["materials"] = json::array({{{"id", "steel"}, {"E", 2.1e11}, {"nu", 0.3}}});
  d["sections"] = json::array({{{"id", "s"}, {"shape", "rectangle"}, {"b", 0.05}, {"h", 0.08}}});
  const auto id = [&](int i, int j, int k) { return std::to_string((k * (ny + 1) + j) * (nx + 1) + i); };
  json nodes = json::array(), elements = json::array(), supports = json::array(), loads = json::array();
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        nodes.push_back({{"id", id(i, j, k)}, {"xyz", {i * 1.0, j * 1.0, k * 1.0}}});
        if (k == 0) supports.push_back({{"node", id(i, j, k)}, {"fix", "all"}});
        if (k == nz) loads.push_back({{"node", id(i, j, k)}, {"force", {1e3, 0.5e3, -2e3}}});
        const auto beam = [&](int i2, int j2, int k2, json orientation) {
          elements.push_back({{"id", id(i, j, k) + "-" + id(i2, j2, k2)}, {"type", "beam"},
                              {"nodes", {id(i, j, k), id(i2, j2, k2)}}, {"material", "steel"}, {"section", "s"},
                              {"orientation", orientation}});
        };
        if (i < nx) beam(i + 1, j, k, {0, 0, 1});
        if (j < ny) beam(i, j + 1, k, {0, 0, 1});
        if (k < nz) beam(i, j, k + 1, {1, 0, 0});
      }
  d["nodes"] = nodes;
  d["elements"] = elements;
  d["supports"] = supports;
  d["loads"] = loads;
  return d;
}

// Two clamped columns and a Timoshenko beam between their tops (4 elements); a rigid arm off one
// top; a revolute joint with a spring carrying an arm off the other; a closed triangle of rigid
// links (over-constrained: its closure rows are redundant) tied to a third clamped column.
json mixed_frame() {
  json d;
  d["materials"] = json::array({{{"id", "steel"}, {"E", 2.1e11}, {"nu", 0.3}}});
  d["sections"] = json::array({{{"id", "r"}, {"shape", "rectangle"}, {"b", 0.05}, {"h", 0.1}}});
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "a"}, {"xyz", {0, 0, 2}}},
                            {{"id", "B"}, {"xyz", {2, 0, 0}}}, {{"id", "b"}, {"xyz", {2, 0, 2}}},
                            {{"id", "r"}, {"xyz", {2.5, 0, 2.5}}}, {{"id", "a2"}, {"xyz", {0, 0, 2}}},
                            {{"id", "t"}, {"xyz", {-1, 0, 2}}}, {{"id", "p"}, {"xyz", {2, 1, 2}}},
                            {{"id", "q"}, {"xyz", {0, 1, 2}}}, {{"id", "Q"}, {"xyz", {0, 1, 0}}}});
  const auto beam = [](const char* id, const char* n0, const char* n1, json orientation) {
    return json{{"id", id}, {"type", "beam"}, {"nodes", {n0, n1}}, {"material", "steel"}, {"section", "r"},
                {"orientation", orientation}};
  };
  json top = beam("ab", "a", "b", {0, 0, 1});
  top["divisions"] = 4;
  top["theory"] = "timoshenko";
  d["elements"] = json::array({beam("Aa", "A", "a", {1, 0, 0}), beam("Bb", "B", "b", {1, 0, 0}), top,
                               beam("a2t", "a2", "t", {0, 0, 1}), beam("Qq", "Q", "q", {1, 0, 0}),
                               {{"id", "arm"}, {"type", "rigid"}, {"nodes", {"b", "r"}}},
                               {{"id", "bp"}, {"type", "rigid"}, {"nodes", {"b", "p"}}},
                               {{"id", "pq"}, {"type", "rigid"}, {"nodes", {"p", "q"}}},
                               {{"id", "qb"}, {"type", "rigid"}, {"nodes", {"q", "b"}}}});
  d["joints"] = json::array(
      {{{"id", "j1"}, {"type", "revolute"}, {"nodes", {"a", "a2"}}, {"axes", {{0, 1, 0}}}, {"stiffness", {2e5}}}});
  d["supports"] = json::array({{{"node", "A"}, {"fix", "all"}}, {{"node", "B"}, {"fix", "all"}}, {{"node", "Q"}, {"fix", "all"}}});
  d["loads"] = json::array({{{"node", "r"}, {"force", {1e3, 2e3, -5e3}}},
                            {{"node", "t"}, {"force", {0, 300, -1e3}}, {"moment", {50, 0, 0}}},
                            {{"node", "p"}, {"moment", {0, 0, 400}}}});
  return d;
}

Model with_solver(json doc, const json& solver) {
  doc["solver"] = solver;
  return test::model_from(doc);
}

// ||F - K u|| / ||F|| over the free DOFs, computed here from the elements' internal forces:
// T_f^T (f_ext - f_int(u)) against T_f^T f_ext (no prescribed values in these models).
double own_residual(const Model& model, const Eigen::VectorXd& u) {
  const DofMap map(model);
  const LinearStructure structure(model);
  const Eigen::VectorXd f = map.reduce(external_force(model, map));
  const Eigen::VectorXd r = map.reduce(external_force(model, map) - structure.internal_force(map, u));
  return r.norm() / f.norm();
}

void expect_iterative_equals_direct(const json& doc) {
  const Model direct = with_solver(doc, {{"type", "direct"}});
  const Model iterative = with_solver(doc, {{"type", "iterative"}, {"rtol", kRtol}});
  const LinearStaticResult d = solve_linear_static(direct);
  const LinearStaticResult i = solve_linear_static(iterative);
  ASSERT_EQ(d.status, SolveStatus::Succeeded) << d.message;
  ASSERT_EQ(i.status, SolveStatus::Succeeded) << i.message;
  EXPECT_FALSE(d.solver.iterative);
  EXPECT_EQ(d.solver.iterations, 1);
  EXPECT_TRUE(i.solver.iterative);
  EXPECT_GT(i.solver.iterations, 1);
  EXPECT_LE(i.solver.residual, kRtol);
  EXPECT_NEAR(i.solver.residual, own_residual(iterative, i.u), kResidualRounding);
  EXPECT_NEAR(d.solver.residual, own_residual(direct, d.u), kResidualRounding);
  EXPECT_LT(d.solver.residual, kResidualRounding);
  const double scale = d.u.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LT((i.u - d.u).cwiseAbs().maxCoeff(), kAgreement * scale);
  for (std::size_t n = 0; n < d.reactions.size(); ++n)
    EXPECT_LT((i.reactions[n] - d.reactions[n]).norm(), kAgreement * (1.0 + d.reactions[n].norm())) << "node " << n;
}

}  // namespace

TEST(IterativeSolver, EqualsTheDirectSolverOnASpaceFrame) { expect_iterative_equals_direct(cube_frame(3, 3, 3)); }

TEST(IterativeSolver, EqualsTheDirectSolverWithJointsRigidLinksAClosedLoopAndTimoshenkoBeams) {
  expect_iterative_equals_direct(mixed_frame());
}

int node_index(const Model& m, const std::string& id) {
  for (std::size_t n = 0; n < m.nodes.size(); ++n)
    if (m.nodes[n].id == id) return static_cast<int>(n);
  return -1;
}

// The stiffness of a node (the condensation K_c = (T_n K^-1 T_n^T)^-1, solvers/condensation.hpp)
// by CG's six solves against the direct condensation, on the free end of the jointed arm and on
// the node of the closed loop of rigid links.
TEST(IterativeSolver, CondensedStiffnessOfANodeEqualsTheDirectOne) {
  for (const char* id : {"t", "p"}) {
    const Model direct = with_solver(mixed_frame(), {{"type", "direct"}});
    const Model iterative = with_solver(mixed_frame(), {{"type", "iterative"}, {"rtol", kRtol}});
    const CondensedStiffness d = linear_node_stiffness(direct, node_index(direct, id));
    const CondensedStiffness i = linear_node_stiffness(iterative, node_index(iterative, id));
    ASSERT_TRUE(d.ok) << d.message;
    ASSERT_TRUE(i.ok) << i.message;
    EXPECT_FALSE(d.solver.iterative);
    EXPECT_EQ(d.solver.iterations, 1);
    EXPECT_LT(d.solver.residual, kResidualRounding) << id;
    EXPECT_TRUE(i.solver.iterative);
    EXPECT_GT(i.solver.iterations, 1);
    EXPECT_LE(i.solver.residual, kRtol);
    EXPECT_EQ(i.rank, d.rank) << id;
    EXPECT_LT((i.compliance - d.compliance).cwiseAbs().maxCoeff(), kAgreement * d.compliance.cwiseAbs().maxCoeff()) << id;
    EXPECT_LT((i.K - d.K).cwiseAbs().maxCoeff(), kAgreement * d.K.cwiseAbs().maxCoeff()) << id;
  }
}

TEST(IterativeSolver, ReportsNotConvergedWithTheResidualReachedAtMaxIterations) {
  const Model m = with_solver(cube_frame(3, 3, 3), {{"type", "iterative"}, {"rtol", kRtol}, {"max_iterations", 2}});
  const LinearStaticResult r = solve_linear_static(m);
  ASSERT_EQ(r.status, SolveStatus::NotConverged) << r.message;
  EXPECT_GT(r.solver.residual, kRtol);
  EXPECT_NE(r.message.find("did not converge: relative residual"), std::string::npos) << r.message;
}

// The two-link chain's revolute joints have no springs: both joint coordinates move freely.
TEST(IterativeSolver, DiagnosesAMechanismNamingWhatMoves) {
  json doc = test::two_link_chain();
  doc["loads"] = json::array({{{"node", "P"}, {"force", {0, 1, 0}}}});
  const LinearStaticResult r = solve_linear_static(with_solver(doc, {{"type", "iterative"}}));
  ASSERT_EQ(r.status, SolveStatus::Mechanism) << r.message;
  EXPECT_NE(r.message.find("mechanism"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("JA"), std::string::npos) << r.message;
}

// Smoothed aggregation given the six rigid-body modes of the frame's nodes needs fewer than half
// the iterations of the same multigrid with only its default (constant) near null space.
TEST(IterativeSolver, RigidBodyModesHalveTheMultigridIterations) {
  const Model m = test::model_from(cube_frame(8, 8, 8));
  const DofMap map(m);
  const LinearStructure structure(m);
  SystemAssembler assembler(map);
  structure.assemble_stiffness(map, assembler);
  const SparseMatrix& K = assembler.K_ff();
  const Eigen::VectorXd f = map.reduce(external_force(m, map));
  const Eigen::MatrixXd modes = rigid_body_modes(m, map);
  ASSERT_EQ(modes.cols(), 6);
  EXPECT_LT((modes.transpose() * modes - Eigen::MatrixXd::Identity(6, 6)).norm(), 1e-12);
  const auto iterations = [&](bool with_modes) {
    PetscSolver cg(IterativeOptions{.rtol = 1e-8});
    if (with_modes) cg.set_near_null_space(modes);
    EXPECT_EQ(cg.compute(K), FactorStatus::Succeeded);
    Eigen::VectorXd u(f.size());
    cg.solve(f, u);
    EXPECT_TRUE(cg.last_solve().converged()) << cg.last_solve().reason;
    return cg.last_solve().iterations;
  };
  const int with = iterations(true), without = iterations(false);
  std::printf("CG iterations with GAMG on %d free DOFs: %d with the rigid-body modes, %d without\n", map.free_size(), with, without);
  EXPECT_LT(2 * with, without);
}

// A rigid motion of the whole unsupported frame strains nothing: K z = 0 for each mode z.
TEST(IterativeSolver, RigidBodyModesAreZeroEnergyModesOfTheUnsupportedFrame) {
  json doc = mixed_frame();
  doc["supports"] = json::array();
  const Model m = test::model_from(doc);
  const DofMap map(m);
  const LinearStructure structure(m);
  SystemAssembler assembler(map);
  structure.assemble_stiffness(map, assembler);
  const Eigen::MatrixXd modes = rigid_body_modes(m, map);
  ASSERT_EQ(modes.cols(), 6);
  const double k = assembler.K_ff().diagonal().maxCoeff();
  EXPECT_LT(Eigen::MatrixXd(assembler.K_ff() * modes).cwiseAbs().maxCoeff(), 1e-9 * k);
}

TEST(IterativeSolver, HypreBoomerAmgEqualsTheDirectSolver) {
  ASSERT_TRUE(petsc_has_hypre()) << "Debian's PETSc (scripts/install-deps.sh) has hypre: the default preconditioner";
  const json doc = cube_frame(3, 3, 2);
  const LinearStaticResult d = solve_linear_static(with_solver(doc, {{"type", "direct"}}));
  const LinearStaticResult h =
      solve_linear_static(with_solver(doc, {{"type", "iterative"}, {"preconditioner", "hypre"}, {"rtol", kRtol}}));
  ASSERT_EQ(h.status, SolveStatus::Succeeded) << h.message;
  EXPECT_LE(h.solver.residual, kRtol);
  EXPECT_LT((h.u - d.u).cwiseAbs().maxCoeff(), kAgreement * d.u.cwiseAbs().maxCoeff());
}

// A process that did not start PETSc on all the processes of a program's MPI (a test, the Python
// module, a sweep's rank: ensure_petsc_initialized) solves alone, and cannot be turned into one
// process of many afterwards: the one-process path is what it was.
TEST(IterativeSolver, SolvesOnThisProcessAloneUnlessTheProgramStartedPetscOnAll) {
  ensure_petsc_initialized();
  EXPECT_EQ(petsc_processes(), 1);
  EXPECT_THROW(initialize_petsc_on_all_processes(), Error);
  EXPECT_EQ(petsc_processes(), 1);
}

// Through the program: results.json's solver report, and the exit codes of the failures.
TEST(IterativeSolverCli, ReportsTheSolverAndExitsOneWhenNotConvergedOrAMechanism) {
  const auto dir = test::temp_dir("iterative_solver_cli");
  json doc = mixed_frame();
  doc["solver"] = {{"type", "iterative"}, {"rtol", kRtol}};
  doc["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}, {{"id", "k"}, {"type", "stiffness"}, {"node", "t"}}});
  test::write_file(dir / "m.json", doc.dump());
  const auto ok = test::run_cli("run " + (dir / "m.json").string() + " --out " + (dir / "out").string() + " --no-vtk -q");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const json solver = test::read_json(dir / "out" / "results.json")["analyses"]["lin"]["solver"];
  EXPECT_EQ(solver["type"], "iterative");
  EXPECT_GT(solver["iterations"].get<int>(), 1);
  EXPECT_LE(solver["residual"].get<double>(), kRtol);
  const json k_solver = test::read_json(dir / "out" / "results.json")["analyses"]["k"]["solver"];
  EXPECT_EQ(k_solver["type"], "iterative");
  EXPECT_LE(k_solver["residual"].get<double>(), kRtol);

  doc["solver"]["max_iterations"] = 2;
  test::write_file(dir / "short.json", doc.dump());
  const auto short_run = test::run_cli("run " + (dir / "short.json").string() + " --out " + (dir / "short").string() + " --no-vtk");
  EXPECT_EQ(short_run.exit_code, 1) << short_run.output;
  EXPECT_NE(short_run.output.find("[lin] not converged"), std::string::npos) << short_run.output;
  EXPECT_NE(short_run.output.find("relative residual"), std::string::npos) << short_run.output;
  EXPECT_NE(short_run.output.find("[k] not converged"), std::string::npos) << short_run.output;

  json chain = test::two_link_chain();
  chain["loads"] = json::array({{{"node", "P"}, {"force", {0, 1, 0}}}});
  chain["solver"] = {{"type", "iterative"}};
  chain["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}});
  test::write_file(dir / "chain.json", chain.dump());
  const auto mech = test::run_cli("run " + (dir / "chain.json").string() + " --out " + (dir / "chain").string() + " --no-vtk");
  EXPECT_EQ(mech.exit_code, 1) << mech.output;
  EXPECT_NE(mech.output.find("mechanism"), std::string::npos) << mech.output;
  EXPECT_NE(mech.output.find("JA"), std::string::npos) << mech.output;
}

}  // namespace iterative_solver_test

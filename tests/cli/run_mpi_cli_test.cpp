// `beamfea run` under mpirun: one model on two processes (the iterative solves distributed over
// them, rank 0 alone writing) gives the one-process answer; a process that fails ends the job.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "support/sweep_util.hpp"

namespace run_mpi_cli_test {

using namespace sweep_test;

namespace {

int sh(const std::string& command) {
  const int s = std::system(command.c_str());
  return WIFEXITED(s) ? WEXITSTATUS(s) : -1;
}

std::string exe() { return BEAMFEA_EXE; }

// As in the sweep's MPI tests: the ranks of the sanitizer build run without leak checking
// (OpenMPI's allocations in plugins it has dlclosed cannot be suppressed).
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kRankEnv = "ASAN_OPTIONS=detect_leaks=0 ";
#else
constexpr const char* kRankEnv = "";
#endif

std::string mpirun(int ranks) {
  return std::string(kRankEnv) + "timeout 300 mpirun --allow-run-as-root --oversubscribe -n " + std::to_string(ranks) + " ";
}

// The relative residual the iterative solves must reach in these tests.
constexpr double kRtol = 1e-12;

// A lattice tower of 11 x 11 x 13 cells of 0.1 m (steel rods), its 144 base nodes clamped, with two
// arms hung from its top corners on revolute joints with torsion springs (about z at one corner,
// about x at the other): 2,016 lattice nodes and 2 x 2 arm nodes, 11,239 free DOFs (the 12,096
// lattice DOFs less 864 clamped, plus 6 for each arm's tip and 1 for each joint). Loaded at a top
// corner and at both arm tips; solved iteratively (CG with GAMG) to kRtol.
json lattice_tower_with_arms() {
  json d;
  d["materials"] = json::array({{{"id", "steel"}, {"E", 2.1e11}, {"G", 8.1e10}}});
  d["sections"] = json::array({{{"id", "rod"}, {"A", 1e-4}, {"Iy", 1e-8}, {"Iz", 1e-8}, {"J", 2e-8}}});
  d["generate"] = {{"lattice", {{"cells", {11, 11, 13}}, {"pitch", 0.1}, {"section", "rod"}, {"material", "steel"}}}};
  d["nodes"] = json::array({{{"id", "a1"}, {"xyz", {1.1, 1.1, 1.3}}}, {{"id", "t1"}, {"xyz", {1.6, 1.1, 1.3}}},
                            {{"id", "a2"}, {"xyz", {0.0, 0.0, 1.3}}}, {{"id", "t2"}, {"xyz", {0.0, -0.5, 1.3}}}});
  d["elements"] = json::array({{{"id", "arm1"}, {"type", "beam"}, {"nodes", {"a1", "t1"}}, {"material", "steel"}, {"section", "rod"}},
                               {{"id", "arm2"}, {"type", "beam"}, {"nodes", {"a2", "t2"}}, {"material", "steel"}, {"section", "rod"}}});
  d["joints"] = json::array({{{"id", "j1"}, {"type", "revolute"}, {"nodes", {"11_11_13", "a1"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {2e3}}},
                             {{"id", "j2"}, {"type", "revolute"}, {"nodes", {"0_0_13", "a2"}}, {"axes", {{1, 0, 0}}}, {"stiffness", {2e3}}}});
  d["supports"] = json::array();
  for (int i = 0; i <= 11; ++i)
    for (int j = 0; j <= 11; ++j) d["supports"].push_back({{"node", std::to_string(i) + "_" + std::to_string(j) + "_0"}, {"fix", "all"}});
  d["loads"] = json::array({{{"node", "11_0_13"}, {"force", {500, 0, 0}}},
                            {{"node", "t1"}, {"force", {0, -200, -100}}},
                            {{"node", "t2"}, {"force", {0, 0, -200}}}});
  d["solver"] = {{"type", "iterative"}, {"rtol", kRtol}};
  d["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}, {{"id", "K"}, {"type", "stiffness"}, {"node", "t1"}}});
  return d;
}

// The largest |a - b| over every node's translations (first three) or rotations (last three) of
// analysis `id`, and the largest |a| of the same kind.
struct Difference {
  double largest_difference = 0.0, largest = 0.0;
};
Difference displacement_difference(const json& a, const json& b, const std::string& id, int first) {
  Difference d;
  for (const auto& [node, ra] : a.at("analyses").at(id).at("nodes").items()) {
    const json& ua = ra.at("displacement");
    const json& ub = b.at("analyses").at(id).at("nodes").at(node).at("displacement");
    for (int k = first; k < first + 3; ++k) {
      d.largest_difference = std::max(d.largest_difference, std::abs(ua[k].get<double>() - ub[k].get<double>()));
      d.largest = std::max(d.largest, std::abs(ua[k].get<double>()));
    }
  }
  return d;
}

double largest_magnitude(const json& j) {
  if (j.is_number()) return std::abs(j.get<double>());
  double m = 0.0;
  if (j.is_structured())
    for (const auto& v : j) m = std::max(m, largest_magnitude(v));
  return m;
}

// Whether results `b` are results `a`: the same keys, strings and counts, and numbers within
// `tolerance` times the largest magnitude of their group (each analyses.<id>.<key>: the nodes'
// displacements and reactions, the elements' end forces ...; exact elsewhere). Wall times and the
// solver's iterations and residual (b's solves are not a's) are not compared.
void expect_same_results(const json& a, const json& b, double tolerance, double scale = 0.0, const std::string& at = "",
                         int depth = 0) {
  ASSERT_EQ(a.type(), b.type()) << at;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << at;
    for (auto it = a.begin(), jt = b.begin(); it != a.end(); ++it, ++jt) {
      ASSERT_EQ(it.key(), jt.key()) << at;
      if (it.key() == "wall_time_s") continue;
      if (it.key() == "solver") {
        EXPECT_EQ(it.value().at("type"), jt.value().at("type")) << at;
        continue;
      }
      const bool group = depth == 2 && at.rfind("/analyses/", 0) == 0;
      expect_same_results(it.value(), jt.value(), tolerance, group ? largest_magnitude(it.value()) : scale,
                          at + "/" + it.key(), depth + 1);
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << at;
    for (std::size_t k = 0; k < a.size(); ++k)
      expect_same_results(a[k], b[k], tolerance, scale, at + "/" + std::to_string(k), depth + 1);
  } else if (a.is_number()) {
    EXPECT_LE(std::abs(a.get<double>() - b.get<double>()), tolerance * scale) << at << ": " << a << " vs " << b;
  } else {
    EXPECT_EQ(a, b) << at;
  }
}

}  // namespace

// Two processes, the same answer. Each iterative solve ends with ||F - K u|| <= rtol ||F||, so
// two answers u1, u2 of one system differ by K^-1 (r1 - r2), at most 2 rtol kappa(K) ||u|| in
// norm. Distributing the rows changes GAMG's aggregates and hence the iterates, not the system:
// the answers agree to that bound, not bit for bit. The bound itself is too loose to test: kappa(K)
// is large here (the rotational and translational stiffnesses of 0.1 m rods alone differ by
// 2e7 / 8e2 ~ 1e4 on the diagonal, the tower's softest bending mode adds orders more), while CG's
// last residual lies in the stiff, high-frequency components, whose K^-1 r is small: the measured
// differences are about 1e-14 of the largest value (rtol 1e-12). kTolerance, 1e4 rtol = 1e-8,
// allows an amplification of the residual by 1e4 (the diagonal's spread), six orders above what
// is measured and as many below what a fault of the distribution gives (a row, a right-hand side
// or a mode on the wrong process: differences of order 1, or no convergence at all).
constexpr double kTolerance = 1e4 * kRtol;

TEST(RunCommandUnderMpirun, TwoRanksGiveTheOneRankAnswerAndRankZeroAloneWrites) {
  ASSERT_EQ(sh("command -v mpirun > /dev/null"), 0) << "mpirun not found: install openmpi-bin libopenmpi-dev "
                                                        "(scripts/install-deps.sh) and rebuild";
  const auto dir = temp_dir("run_mpi");
  const auto model = dir / "model.json";
  write(model, lattice_tower_with_arms().dump());
  const auto one = dir / "one", two = dir / "two", other = dir / "two.other_rank";
  ASSERT_EQ(sh(exe() + " run " + model.string() + " --out " + one.string() + " -q"), 0);
  // Every rank runs the same command but rank 1 names another output folder: rank 0 alone writes,
  // so that folder must never appear.
  write(dir / "rank.sh", "#!/bin/sh\n"
                         "out=" + two.string() + "\n"
                         "[ \"$OMPI_COMM_WORLD_RANK\" = 0 ] || out=" + other.string() + "\n"
                         "exec " + exe() + " run " + model.string() + " --out \"$out\"\n");
  ASSERT_EQ(sh("chmod +x " + (dir / "rank.sh").string()), 0);
  const auto log = dir / "two.txt";
  ASSERT_EQ(sh(mpirun(2) + (dir / "rank.sh").string() + " > " + log.string() + " 2>&1"), 0) << read(log);
  EXPECT_FALSE(fs::exists(other)) << "a rank other than 0 wrote";
  const std::string text = read(log);
  EXPECT_NE(text.find("one model on 2 processes"), std::string::npos) << text;
  std::size_t wrote = 0;
  for (std::size_t at = text.find("beamfea: wrote"); at != std::string::npos; at = text.find("beamfea: wrote", at + 1)) ++wrote;
  EXPECT_EQ(wrote, 1u) << text;
  for (const auto& e : fs::directory_iterator(two))
    EXPECT_EQ(e.path().filename().string().rfind(".beamfea-staging", 0), std::string::npos) << e.path();

  const json r1 = json::parse(read(one / "results.json"));
  const json r2 = json::parse(read(two / "results.json"));
  for (const char* id : {"lin", "K"}) {
    const json& s1 = r1["analyses"][id]["solver"];
    const json& s2 = r2["analyses"][id]["solver"];
    EXPECT_EQ(s2["type"], "iterative") << id;
    EXPECT_LE(s1["residual"].get<double>(), kRtol) << id;
    EXPECT_LE(s2["residual"].get<double>(), kRtol) << id;
  }
  for (int first : {0, 3}) {
    const Difference d = displacement_difference(r1, r2, "lin", first);
    ASSERT_GT(d.largest, 0.0);
    EXPECT_LE(d.largest_difference, kTolerance * d.largest)
        << (first ? "rotations" : "translations") << ": relative difference " << d.largest_difference / d.largest;
  }
  // The whole file is the one-process file: the condensed stiffness of the arm's tip (six solves,
  // then the inverse of their 6 x 6 answer), the end forces, the reactions, the joints' forces.
  expect_same_results(r1, r2, kTolerance);
}

// A process that fails ends every process with one message naming it, and nothing is written:
// before the run (rank 1 cannot read the model: all exit 2 together), during it (rank 1 meets
// bad input of its own once rank 0 is solving: it ends the job while rank 0 waits for it), and
// inside an analysis.
TEST(RunCommandUnderMpirun, ARankThatFailsEndsAllRanksWithOneMessageAndNothingWritten) {
  ASSERT_EQ(sh("command -v mpirun > /dev/null"), 0) << "mpirun not found";
  const auto dir = temp_dir("run_mpi_fail");
  const auto model = dir / "model.json";
  write(model, lattice_tower_with_arms().dump());
  struct Case {
    std::string name, rank1_args, message;
    int code;
  };
  for (const Case& c : {Case{"unreadable", (dir / "missing.json").string(), "rank 1 of 2", 2},
                        Case{"late", model.string() + " --analysis nope", "rank 1 of 2: --analysis 'nope'", 2}}) {
    const auto out = dir / c.name;
    write(dir / "rank.sh", "#!/bin/sh\n"
                           "args=" + model.string() + "\n"
                           "[ \"$OMPI_COMM_WORLD_RANK\" = 0 ] || args=\"" + c.rank1_args + "\"\n"
                           "exec " + exe() + " run $args --out " + out.string() + "\n");
    ASSERT_EQ(sh("chmod +x " + (dir / "rank.sh").string()), 0);
    const auto log = dir / (c.name + ".txt");
    const int rc = sh(mpirun(2) + (dir / "rank.sh").string() + " > " + log.string() + " 2>&1");
    const std::string text = read(log);
    EXPECT_EQ(rc, c.code) << c.name << ":\n" << text;
    EXPECT_NE(text.find(c.message), std::string::npos) << c.name << ":\n" << text;
    std::size_t messages = 0;
    for (std::size_t at = text.find("beamfea: error"); at != std::string::npos; at = text.find("beamfea: error", at + 1)) ++messages;
    EXPECT_EQ(messages, 1u) << c.name << ":\n" << text;
    EXPECT_FALSE(fs::exists(out / "results.json")) << c.name;
  }
  // An analysis that throws (here PETSc, told to use a KSP type it does not have; the same on both
  // ranks): one process reports the analysis as failed in results.json, several end the job, since
  // such an error may strike one process alone while the others wait in a collective call.
  const auto out = dir / "petsc_error";
  const auto log = dir / "petsc_error.txt";
  const int rc = sh("PETSC_OPTIONS='-ksp_type no_such_type' " + mpirun(2) + "-x PETSC_OPTIONS " + exe() + " run " +
                    model.string() + " --out " + out.string() + " -q > " + log.string() + " 2>&1");
  const std::string text = read(log);
  EXPECT_EQ(rc, 1) << text;
  EXPECT_NE(text.find("of 2: analysis 'lin': PETSc: KSPSetFromOptions failed"), std::string::npos) << text;
  std::size_t messages = 0;
  for (std::size_t at = text.find("beamfea: error"); at != std::string::npos; at = text.find("beamfea: error", at + 1)) ++messages;
  EXPECT_EQ(messages, 1u) << text;
  EXPECT_FALSE(fs::exists(out / "results.json"));
}

// A mechanism under two processes is named as under one: each process assembles only its share of
// the stiffness, and the diagnosis (which reads the whole) assembles it whole. A 5 x 5 x 6 lattice
// tower with an arm on a revolute joint without a spring: the arm swings about z.
TEST(RunCommandUnderMpirun, AMechanismIsNamedAsOnOneProcess) {
  const auto dir = temp_dir("run_mpi_mechanism");
  json d;
  d["materials"] = json::array({{{"id", "steel"}, {"E", 2.1e11}, {"G", 8.1e10}}});
  d["sections"] = json::array({{{"id", "rod"}, {"A", 1e-4}, {"Iy", 1e-8}, {"Iz", 1e-8}, {"J", 2e-8}}});
  d["generate"] = {{"lattice", {{"cells", {5, 5, 6}}, {"pitch", 0.1}, {"section", "rod"}, {"material", "steel"}}}};
  d["nodes"] = json::array({{{"id", "a1"}, {"xyz", {0.5, 0.5, 0.6}}}, {{"id", "t1"}, {"xyz", {1.0, 0.5, 0.6}}}});
  d["elements"] = json::array({{{"id", "arm1"}, {"type", "beam"}, {"nodes", {"a1", "t1"}}, {"material", "steel"}, {"section", "rod"}}});
  d["joints"] = json::array({{{"id", "j1"}, {"type", "revolute"}, {"nodes", {"5_5_6", "a1"}}, {"axes", {{0, 0, 1}}}}});
  d["supports"] = json::array();
  for (int i = 0; i <= 5; ++i)
    for (int j = 0; j <= 5; ++j) d["supports"].push_back({{"node", std::to_string(i) + "_" + std::to_string(j) + "_0"}, {"fix", "all"}});
  d["loads"] = json::array({{{"node", "t1"}, {"force", {0, -200, -100}}}});
  d["solver"] = {{"type", "iterative"}, {"rtol", kRtol}};
  d["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}});
  const auto model = dir / "model.json";
  write(model, d.dump());
  EXPECT_EQ(sh(exe() + " run " + model.string() + " --out " + (dir / "one").string() + " -q"), 1);
  const auto log = dir / "two.txt";
  EXPECT_EQ(sh(mpirun(2) + exe() + " run " + model.string() + " --out " + (dir / "two").string() + " -q > " + log.string() +
               " 2>&1"), 1) << read(log);
  const json r1 = json::parse(read(dir / "one" / "results.json"));
  const json r2 = json::parse(read(dir / "two" / "results.json"));
  const std::string m1 = r1["analyses"]["lin"]["message"], m2 = r2["analyses"]["lin"]["message"];
  EXPECT_NE(m1.find("mechanism"), std::string::npos) << m1;
  EXPECT_NE(m1.find("joint 'j1' coordinate 0"), std::string::npos) << m1;
  EXPECT_EQ(m2, m1);
}

// An eigen-analysis on SLEPc under two processes is distributed too (above the 20,000 DOFs up to
// which its inner solves are factorised on each process) and gives the one-process modes. A 15^3
// lattice of aluminium rods (benchmarks/lattice_model.py 15 --eigen: 23,040 free DOFs), its two
// lowest modes: a degenerate pair (the lattice is square), so that only their frequencies and the
// pair's summed effective masses are defined. SLEPc stops at a relative residual of rtol 1e-10,
// which bounds each omega^2's error by about that (Rayleigh quotient of a residual-rtol vector);
// 1e-8 of the frequencies allows a hundred times that, and a fault of the distribution (a row or
// a mode on the wrong process) changes them at the first digit or does not converge.
TEST(RunCommandUnderMpirun, AModalAnalysisOnSlepcGivesTheOneProcessModes) {
  const auto dir = temp_dir("run_mpi_modal");
  const int n = 15;
  json d;
  d["materials"] = json::array({{{"id", "al"}, {"E", 70e9}, {"G", 26e9}, {"density", 2700}}});
  d["sections"] = json::array({{{"id", "rod"}, {"shape", "circle"}, {"d", 0.002}}});
  d["generate"] = {{"lattice", {{"cells", {n, n, n}}, {"pitch", 0.01}, {"section", "rod"}, {"material", "al"}}}};
  d["supports"] = json::array();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) d["supports"].push_back({{"node", std::to_string(i) + "_" + std::to_string(j) + "_0"}, {"fix", "all"}});
  d["solver"] = {{"type", "iterative"}, {"rtol", 1e-10}};
  d["analyses"] = json::array({{{"id", "m"}, {"type", "modal"}, {"modes", 2}}});
  const auto model = dir / "model.json";
  write(model, d.dump());
  ASSERT_EQ(sh(exe() + " run " + model.string() + " --out " + (dir / "one").string() + " --no-vtk -q"), 0);
  const auto log = dir / "two.txt";
  ASSERT_EQ(sh(mpirun(2) + exe() + " run " + model.string() + " --out " + (dir / "two").string() + " --no-vtk > " +
               log.string() + " 2>&1"), 0) << read(log);
  const json m1 = json::parse(read(dir / "one" / "results.json"))["analyses"]["m"];
  const json m2 = json::parse(read(dir / "two" / "results.json"))["analyses"]["m"];
  EXPECT_EQ(m1["free_dofs"], 23040);
  EXPECT_EQ(m2["solver"]["type"], "iterative");
  EXPECT_GT(m2["solver"]["linear_iterations"].get<long long>(), 0) << "the inner solves were factorised, not distributed";
  ASSERT_EQ(m1["frequencies"].size(), 2u);
  ASSERT_EQ(m2["frequencies"].size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const double f1 = m1["frequencies"][k], f2 = m2["frequencies"][k];
    EXPECT_NEAR(f2, f1, 1e-8 * f1) << "mode " << k;
  }
  // The pair's effective masses in x and y (each about three quarters of the moving mass) agree
  // to what the eigen-tolerance leaves in the vectors.
  for (const char* dof : {"ux", "uy"}) {
    const double e1 = m1["effective_mass_sum"][dof], e2 = m2["effective_mass_sum"][dof];
    EXPECT_GT(e1, 0.5) << dof;
    EXPECT_NEAR(e2, e1, 1e-6 * e1) << dof;
  }
}

// Without mpirun nothing changes: one process, no MPI started by the program, the same solve
// (the tower's answer equal to the direct solver's to the same bound as above).
TEST(RunCommand, WithoutMpirunTheRunIsOneProcessAsBefore) {
  const auto dir = temp_dir("run_no_mpi");
  json d = lattice_tower_with_arms();
  d["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}});
  write(dir / "iterative.json", d.dump());
  d["solver"] = {{"type", "direct"}};
  write(dir / "direct.json", d.dump());
  const auto log = dir / "log.txt";
  ASSERT_EQ(sh(exe() + " run " + (dir / "iterative.json").string() + " --out " + (dir / "it").string() + " > " +
               log.string() + " 2>&1"), 0) << read(log);
  EXPECT_EQ(read(log).find("processes"), std::string::npos) << read(log);
  ASSERT_EQ(sh(exe() + " run " + (dir / "direct.json").string() + " --out " + (dir / "dir").string() + " -q"), 0);
  const json it = json::parse(read(dir / "it" / "results.json"));
  const json di = json::parse(read(dir / "dir" / "results.json"));
  EXPECT_EQ(it["analyses"]["lin"]["solver"]["type"], "iterative");
  for (int first : {0, 3}) {
    const Difference diff = displacement_difference(di, it, "lin", first);
    EXPECT_LE(diff.largest_difference, kTolerance * diff.largest) << diff.largest_difference / diff.largest;
  }
}

// The user's PETSC_OPTIONS reach SLEPc's eigen-solver and its inner linear solve (-eps_*, -st_ksp_*,
// -st_pc_*), read after beamfea's own settings: a KSP type this PETSc does not have, given to the
// shift-and-invert's KSP alone, fails the modal analysis (reported in results.json, exit 1) and names where; without it the same run
// succeeds.
TEST(RunCommand, TheUsersPetscOptionsReachTheEigenSolversInnerSolve) {
  const auto dir = temp_dir("run_slepc_options");
  json d;
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {1, 0, 0}}}});
  d["materials"] = json::array({{{"id", "steel"}, {"E", 2.1e11}, {"G", 8.1e10}, {"density", 7850}}});
  d["sections"] = json::array({{{"id", "rod"}, {"A", 1e-4}, {"Iy", 1e-8}, {"Iz", 2e-8}, {"J", 2e-8}}});
  d["elements"] = json::array({{{"id", "e"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "steel"},
                                {"section", "rod"}, {"divisions", 8}}});
  d["supports"] = json::array({{{"node", "A"}, {"fix", "all"}}});
  d["solver"] = {{"type", "iterative"}};
  d["analyses"] = json::array({{{"id", "m"}, {"type", "modal"}, {"modes", 3}}});
  write(dir / "m.json", d.dump());
  const auto log = dir / "log.txt";
  ASSERT_EQ(sh(exe() + " run " + (dir / "m.json").string() + " --out " + (dir / "ok").string() + " -q > " +
               log.string() + " 2>&1"), 0) << read(log);
  const int rc = sh("PETSC_OPTIONS='-st_ksp_type no_such_type' " + exe() + " run " + (dir / "m.json").string() +
                    " --out " + (dir / "bad").string() + " -q > " + log.string() + " 2>&1");
  const std::string text = read(log);
  EXPECT_EQ(rc, 1) << text;
  const json bad = json::parse(read(dir / "bad" / "results.json"));
  EXPECT_EQ(bad["analyses"]["m"]["status"], "failed");
  EXPECT_NE(bad["analyses"]["m"]["message"].get<std::string>().find("EPSSetFromOptions failed (Unknown type"),
            std::string::npos) << bad["analyses"]["m"]["message"];
  const json ok = json::parse(read(dir / "ok" / "results.json"));
  EXPECT_EQ(ok["analyses"]["m"]["frequencies"].size(), 3u);
}

}  // namespace run_mpi_cli_test

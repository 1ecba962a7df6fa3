// The libraries' OpenMP regions on one thread (app/openmp.hpp): when the program leaves the choice to
// the user, that CHOLMOD then starts no OpenMP threads and still solves exactly, and what
// `beamfea --version` says.
#include "app/openmp.hpp"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

#include "solvers/sparse_factor.hpp"
#include "support/matrices.hpp"
#include "support/models.hpp"

namespace openmp_test {

using beamfea::app::user_sets_openmp;

namespace {

// Threads of this process, from /proc/self/task.
int thread_count() {
  int n = 0;
  for ([[maybe_unused]] const auto& t : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

}  // namespace

TEST(LibraryOpenMp, OnlyTheVariablesThatSizeTeamsAreTheUsersChoice) {
  EXPECT_FALSE(user_sets_openmp(nullptr));
  const char* none[] = {nullptr};
  EXPECT_FALSE(user_sets_openmp(none));
  const char* others[] = {"PATH=/usr/bin", "OMP_PROC_BIND=true", "XOMP_NUM_THREADS=2", "OMP_NUM_THREADS", nullptr};
  EXPECT_FALSE(user_sets_openmp(others));
  for (const char* v : {"OMP_NUM_THREADS=2", "OMP_THREAD_LIMIT=1", "OMP_MAX_ACTIVE_LEVELS=0", "OMP_DYNAMIC=true",
                        "OMP_NUM_THREADS="}) {
    const char* env[] = {"HOME=/root", v, nullptr};
    EXPECT_TRUE(user_sets_openmp(env)) << v;
  }
}

// CHOLMOD opens its four-thread regions on supernodes this large (the top separator of a 22^3
// grid has about 500 columns). After the setting, a factorisation adds no thread to the process
// and its solution is exact to a few ulps (the matrix is well conditioned). Without the setting
// the same test counts three more threads (2 -> 5, checked by leaving the call out).
TEST(LibraryOpenMp, CholmodStartsNoThreadAfterTheSetting) {
  // The program's choice is what is tested: an OMP_ variable of the caller's environment would
  // make it the user's (read by serialize_library_openmp from environ, not by the runtime again).
  for (const char* name : {"OMP_NUM_THREADS", "OMP_THREAD_LIMIT", "OMP_MAX_ACTIVE_LEVELS", "OMP_DYNAMIC"})
    unsetenv(name);
  // Debian's CHOLMOD, linked into this test, loads GCC's OpenMP runtime: the setting must be made.
  ASSERT_TRUE(beamfea::app::serialize_library_openmp());
  using GetLevels = int (*)();
  const auto get_levels = reinterpret_cast<GetLevels>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
  ASSERT_NE(get_levels, nullptr);
  EXPECT_EQ(get_levels(), 0);

  const beamfea::SparseMatrix K = beamfea::test::grid_laplacian(22);
  Eigen::VectorXd x(K.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = std::cos(0.41 * static_cast<double>(i)) + 0.2 * (i % 3);
  const Eigen::VectorXd f = K * x;
  // On the calling thread, and on a thread started afterwards that repeats the choice (a sweep's
  // worker; without apply_library_openmp_to_this_thread it would start from the runtime's defaults).
  auto factorise = [&] {
    const int before = thread_count();
    beamfea::SparseFactor factor;
    ASSERT_EQ(factor.factorize(K), beamfea::FactorStatus::Succeeded);
    EXPECT_EQ(thread_count(), before);
    EXPECT_LT((factor.solve(f) - x).norm() / x.norm(), 1e-13);
  };
  std::thread worker([&] {
    beamfea::app::apply_library_openmp_to_this_thread();
    factorise();
  });
  worker.join();
  factorise();
}

TEST(LibraryOpenMp, VersionSaysWhetherTheProgramChose) {
  const auto chosen = beamfea::test::run_cli_with_prefix("env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT "
                                                         "-u OMP_MAX_ACTIVE_LEVELS -u OMP_DYNAMIC ", "--version");
  ASSERT_EQ(chosen.exit_code, 0) << chosen.output;
  EXPECT_NE(chosen.output.find("OpenMP: the libraries' parallel regions on one thread"), std::string::npos)
      << chosen.output;
  const auto user = beamfea::test::run_cli_with_prefix("OMP_NUM_THREADS=2 ", "--version");
  ASSERT_EQ(user.exit_code, 0) << user.output;
  EXPECT_NE(user.output.find("OpenMP: as the environment says"), std::string::npos) << user.output;
}

}  // namespace openmp_test

// The solvers' BLAS-thread hook (solvers/blas_threads.hpp): a path runs with one BLAS thread through
// the hook the program installs, and gives the previous number back when it ends; without a hook the
// BLAS is not touched.
#include <gtest/gtest.h>

#include <vector>

#include "path_models.hpp"
#include "solvers/blas_threads.hpp"
#include "solvers/path_following.hpp"

namespace blas_threads_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
// A fake BLAS: its thread count and every call of the hook.
struct FakeBlas {
  int threads = 4;
  std::vector<int> calls;
};
}  // namespace

TEST(BlasThreads, ScopeSetsOneThreadAndRestoresThePreviousNumber) {
  FakeBlas blas;
  install_blas_threads_hook([&](int n) {
    blas.calls.push_back(n);
    const int previous = blas.threads;
    blas.threads = n;
    return previous;
  });
  {
    const SingleBlasThread one;
    EXPECT_EQ(blas.threads, 1);
  }
  EXPECT_EQ(blas.threads, 4);
  EXPECT_EQ(blas.calls, (std::vector<int>{1, 4}));

  // A path holds one thread for its whole run (its progress lines are seen with one thread).
  blas.calls.clear();
  const Model m = read_model(lees_frame(1.0));
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length_auto = true;
  o.max_steps = 3;
  std::vector<int> seen;
  o.progress = [&](const std::string&) { seen.push_back(blas.threads); };
  const PathResult r = follow_path(m, o);
  EXPECT_EQ(r.steps.size(), 4u) << r.brief_report();
  ASSERT_FALSE(seen.empty());
  for (int t : seen) EXPECT_EQ(t, 1);
  EXPECT_EQ(blas.threads, 4);
  EXPECT_EQ(blas.calls.front(), 1);
  EXPECT_EQ(blas.calls.back(), 4);

  // Already one thread (a sweep): nothing to restore.
  blas.threads = 1;
  blas.calls.clear();
  { const SingleBlasThread one; }
  EXPECT_EQ(blas.calls, (std::vector<int>{1}));
  EXPECT_EQ(blas.threads, 1);

  // No hook: nothing is called.
  install_blas_threads_hook({});
  blas.calls.clear();
  { const SingleBlasThread one; }
  EXPECT_TRUE(blas.calls.empty());
}

}  // namespace blas_threads_test

// The OpenBLAS kernel choice (app/openblas.hpp): when the program replaces OpenBLAS's own choice,
// and that a replaced choice still factorises correctly.
#include "app/openblas.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

#include "solvers/sparse_factor.hpp"
#include "support/matrices.hpp"

namespace openblas_test {

using beamfea::app::better_openblas_core;
using beamfea::app::CpuVectorUnits;

namespace {

constexpr CpuVectorUnits kNone{false, false};
constexpr CpuVectorUnits kAvx2{true, false};
constexpr CpuVectorUnits kAvx512{true, true};

}  // namespace

TEST(OpenBlasCore, PrescottFallbackIsReplacedByWhatTheCpuSupports) {
  EXPECT_EQ(better_openblas_core("Prescott", false, kAvx512), "SkylakeX");
  EXPECT_EQ(better_openblas_core("prescott", false, kAvx2), "Haswell");
}

TEST(OpenBlasCore, OtherwiseOpenBlasKeepsItsChoice) {
  // A CPU without AVX2: Prescott may be right there.
  EXPECT_FALSE(better_openblas_core("Prescott", false, kNone));
  // The user chose (OPENBLAS_CORETYPE set), even Prescott.
  EXPECT_FALSE(better_openblas_core("Prescott", true, kAvx512));
  // OpenBLAS recognised the CPU.
  EXPECT_FALSE(better_openblas_core("Haswell", false, kAvx512));
  EXPECT_FALSE(better_openblas_core("Zen", false, kAvx2));
  EXPECT_FALSE(better_openblas_core("", false, kAvx512));
}

// On the loaded BLAS: after the choice, OpenBLAS is not left on the generic kernels of a CPU with
// AVX2, and CHOLMOD (supernodal, dgemm/dsyrk/dpotrf on the new kernels) still solves exactly.
// Another BLAS is reported as such (no core, nothing replaced) and must solve exactly too.
TEST(OpenBlasCore, ChosenKernelsFactoriseCorrectly) {
  const char* set = std::getenv("OPENBLAS_CORETYPE");
  const auto blas = beamfea::app::choose_openblas_core();
  if (!blas.openblas) {
    EXPECT_EQ(blas.core, "");
    EXPECT_EQ(blas.replaced, "");
  } else if (!set && beamfea::app::cpu_vector_units().avx2_fma) {
    EXPECT_STRCASENE(blas.core.c_str(), "Prescott");
  }
  if (!blas.replaced.empty()) {
    EXPECT_STRCASEEQ(blas.replaced.c_str(), "Prescott");
  }
  EXPECT_EQ(std::getenv("OPENBLAS_CORETYPE") == nullptr, set == nullptr);  // environment as it was

  // A 3-D grid Laplacian plus the identity, 12^3 = 1728 unknowns: above the dense threshold, with
  // supernodes large enough for BLAS-3 calls. Its exact solution is chosen, the load computed.
  const beamfea::SparseMatrix K = beamfea::test::grid_laplacian(12);
  const int n = static_cast<int>(K.rows());
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = std::sin(0.37 * i) + 0.1 * (i % 5);
  const Eigen::VectorXd f = K * x;
  beamfea::SparseFactor factor;
  ASSERT_EQ(factor.factorize(K), beamfea::FactorStatus::Succeeded);
  EXPECT_FALSE(factor.dense());
  // K is well conditioned (eigenvalues in [1, 13]): the error is a few ulps of |x|.
  EXPECT_LT((factor.solve(f) - x).norm() / x.norm(), 1e-13);
}

}  // namespace openblas_test

// Small models: where a dense factorisation beats CHOLMOD (the threshold kDenseMaxDofs in
// solvers/sparse_factor.hpp), and stiffness analyses per second of the three-link chain (the
// chain of bench_sweep_rate: 63 DOFs) on one core. "SparseFactor dense" is the whole dense path
// (copy to dense, Jacobi scaling, the zero-skipping factor of solvers/dense_condensation.hpp, a
// solve); "bare factor" the factor and substitutions alone on a dense copy.
//
// Usage: taskset -c 0 bench_small_models [seconds_per_point]
// Prints Markdown tables (docs/performance.md, "Small models"). Every time is the thread's CPU
// time per call, median of 5 batches of repeated calls, the variants interleaved batch by batch
// (paired). OpenBLAS is held to one thread.
#include <fmt/format.h>

#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cstdlib>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/assembly.hpp"
#include "app/openblas.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/dense_condensation.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"
#include "bench_models.hpp"
#include "bench_timing.hpp"

using json = nlohmann::json;
using namespace beamfea;

namespace {

using beamfea::bench::chain;  // the chain of bench_sweep_rate (63 DOFs)
using beamfea::bench::material_and_section;

// A cantilever of `m` elements (banded K, 6 m DOFs).
json cantilever(int m) {
  json d = material_and_section();
  d["nodes"] = json::array();
  d["elements"] = json::array();
  for (int i = 0; i <= m; ++i) d["nodes"].push_back({{"id", fmt::format("n{}", i)}, {"xyz", {0.1 * i, 0, 0}}});
  for (int i = 0; i < m; ++i)
    d["elements"].push_back({{"id", fmt::format("e{}", i)}, {"type", "beam"},
                             {"nodes", {fmt::format("n{}", i), fmt::format("n{}", i + 1)}}, {"material", "al"}, {"section", "link"}});
  d["supports"] = {json{{"node", "n0"}, {"fix", "all"}}};
  return d;
}

// An n x n x n lattice clamped at z = 0 (6 n^2 (n - 1) free DOFs, 3-D fill).
json lattice(int n) {
  json m = material_and_section();
  m["nodes"] = json::array();
  m["elements"] = json::array();
  auto id = [](int i, int j, int k) { return fmt::format("n{}_{}_{}", i, j, k); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) m["nodes"].push_back({{"id", id(i, j, k)}, {"xyz", {i, j, k}}});
  int e = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        auto beam = [&](int i2, int j2, int k2) {
          if (i2 >= n || j2 >= n || k2 >= n) return;
          m["elements"].push_back({{"id", fmt::format("e{}", e++)}, {"type", "beam"}, {"nodes", {id(i, j, k), id(i2, j2, k2)}},
                                   {"material", "al"}, {"section", "link"}});
        };
        beam(i + 1, j, k);
        beam(i, j + 1, k);
        beam(i, j, k + 1);
      }
  m["supports"] = json::array();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m["supports"].push_back({{"node", id(i, j, 0)}, {"fix", "all"}});
  return m;
}

SparseMatrix stiffness(const Model& model, const DofMap& map) {
  const LinearStructure structure(model);
  SystemAssembler a(map);
  a.begin();
  structure.assemble(map, a);
  a.end();
  return a.K_ff();
}

}  // namespace

int main(int argc, char** argv) {
  beamfea::app::set_blas_threads(1);
  const double budget = argc > 1 ? std::atof(argv[1]) : 0.5;

  fmt::print("### SparseFactor::factorize + solve: dense Cholesky against CHOLMOD\n\n");
  fmt::print("| model | free DOFs | CHOLMOD us | SparseFactor dense us | bare factor us | CHOLMOD / dense | CHOLMOD / bare |\n"
             "|---|---:|---:|---:|---:|---:|---:|\n");
  std::vector<std::pair<std::string, json>> models;
  for (int m : {2, 5, 10, 15, 20, 27, 30, 40, 60}) models.emplace_back(fmt::format("cantilever {}", m), cantilever(m));
  for (int n : {2, 3, 4}) models.emplace_back(fmt::format("lattice {}^3", n), lattice(n));
  models.emplace_back("three-link chain", chain());
  for (const auto& [name, doc] : models) {
    const Model model = read_model(doc);
    const DofMap map(model);
    const SparseMatrix K = stiffness(model, map);
    const int n = static_cast<int>(K.rows());
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
    FactorOptions dense, sparse;
    dense.dense_max_dofs = n;
    sparse.dense_max_dofs = 0;
    volatile double sink = 0;
    // The condensation's factor (solvers/dense_condensation.hpp): the dense copy, the factor that
    // skips zeros, and one forward and back substitution.
    const Eigen::MatrixXd Kd(K);
    auto zero_skipping = [&] {
      Eigen::MatrixXd L = Kd;
      std::vector<int> last;
      cholesky_in_place(L, last);
      Eigen::VectorXd x = b;
      for (int k = 0; k < n; ++k) {
        x[k] /= L(k, k);
        for (int i = k + 1; i <= last[k]; ++i) x[i] -= L(i, k) * x[k];
      }
      for (int k = n; k-- > 0;) {
        for (int i = k + 1; i <= last[k]; ++i) x[k] -= L(i, k) * x[i];
        x[k] /= L(k, k);
      }
      sink = sink + x[0];
    };
    const auto t = bench::paired({[&] { SparseFactor f; f.factorize(K, sparse); sink = sink + f.solve(b)[0]; },
                           [&] { SparseFactor f; f.factorize(K, dense); sink = sink + f.solve(b)[0]; }, zero_skipping},
                          budget);
    fmt::print("| {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.2f} | {:.2f} |\n", name, n, 1e6 * t[0], 1e6 * t[1], 1e6 * t[2],
               t[0] / t[1], t[0] / t[2]);
  }

  const json doc = chain();
  const Model model = read_model(doc);
  const int tip = model.find_node("T");
  const DofMap map(model);
  const SparseMatrix K = stiffness(model, map);
  const int n = static_cast<int>(K.rows());
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(6, n);
  for (int k = 0; k < 6; ++k)
    for (SparseRowMatrix::InnerIterator it(map.T_free(), map.raw_node(tip, k)); it; ++it) rows(k, it.col()) += it.value();
  // The saddle point [K A^T; A 0] by UMFPACK, as condensed_stiffness did before the dense path.
  auto saddle_lu = [&] {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(K.nonZeros() + 12 * 6);
    for (int j = 0; j < K.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(K, j); it; ++it) t.emplace_back(static_cast<int>(it.row()), j, it.value());
    for (int k = 0; k < 6; ++k)
      for (int j = 0; j < n; ++j)
        if (rows(k, j) != 0.0) {
          t.emplace_back(n + k, j, rows(k, j));
          t.emplace_back(j, n + k, rows(k, j));
        }
    SparseMatrix S(n + 6, n + 6);
    S.setFromTriplets(t.begin(), t.end());
    S.makeCompressed();
    Eigen::UmfPackLU<SparseMatrix> lu(S);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + 6, 6);
    rhs.bottomRows(6).setIdentity();
    const Eigen::MatrixXd X = lu.solve(rhs);
    return Eigen::MatrixXd(X.bottomRows(6));
  };
  volatile double sink = 0;
  const auto tc = bench::paired({[&] { sink = sink + saddle_lu()(0, 0); },
                          [&] { Eigen::MatrixXd Kz; condense(K, rows, Kz); sink = sink + Kz(0, 0); }},
                         budget);
  const auto ta = bench::paired({[&] { sink = sink + linear_node_stiffness(model, tip).K(0, 0); },
                          [&] {
                            const Model m = load_and_check(doc);
                            sink = sink + static_cast<double>(run_document(m, doc, {}).failed);
                          }},
                         budget);
  fmt::print("\n### Three-link chain (stiffness at the tip, {} free DOFs), one core\n\n", n);
  fmt::print("| stage | us per call | calls per second |\n|---|---:|---:|\n");
  fmt::print("| condensation: saddle point by UMFPACK (baseline) | {:.1f} | {:.0f} |\n", 1e6 * tc[0], 1 / tc[0]);
  fmt::print("| condensation: dense Schur complement (used) | {:.1f} | {:.0f} |\n", 1e6 * tc[1], 1 / tc[1]);
  fmt::print("| linear_node_stiffness (DOF map, assembly, condensation, rank) | {:.1f} | {:.0f} |\n", 1e6 * ta[0], 1 / ta[0]);
  fmt::print("| load_and_check + run_document (the model from parsed JSON, results object) | {:.1f} | {:.0f} |\n",
             1e6 * ta[1], 1 / ta[1]);
}

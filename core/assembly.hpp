#pragma once
// Assembly of the reduced system through a DofMap.
//
// Elements give matrices and vectors over their raw DOFs; the assembler maps them through the
// constraint transformation, raw u = T_f u_free + T_p u_prescribed:
//   K_ff += T_f,e^T K_e T_f,e      K_fp += T_f,e^T K_e T_p,e
// The first assembly builds the CSC pattern from triplets; later assemblies with the same
// sequence of calls write straight into the values (the pattern, and hence the symbolic
// factorisation, is reused). Or the pattern of K_ff is planned before any element matrix exists,
// from the raw DOFs each call will name (`plan`): the first assembly then writes into it too, and
// the pattern can be ordered and analysed while the element matrices are computed
// (solvers/linear_static.cpp).
#include <Eigen/SparseCore>
#include <limits>
#include <span>
#include <vector>

#include "core/dof_map.hpp"

namespace beamfea {

// The raw DOFs of each `add` call of an assembly, in the order of the calls: block b is
// raw[start[b]] .. raw[start[b + 1] - 1].
struct AssemblyBlocks {
  std::vector<int> start{0};
  std::vector<int> raw;
  void add(std::span<const int> dofs) {
    raw.insert(raw.end(), dofs.begin(), dofs.end());
    start.push_back(static_cast<int>(raw.size()));
  }
  std::size_t size() const { return start.size() - 1; }
  std::span<const int> block(std::size_t b) const {
    return {raw.data() + start[b], static_cast<std::size_t>(start[b + 1] - start[b])};
  }
};

// The pattern of K_ff (free x free, both triangles, rows sorted in each column, every value zero)
// that an assembly of `blocks` through `map` makes: the entries (i, j) with i and j among the free
// DOFs that the T_f rows of one block's raw DOFs reach, explicit zeros of the element matrices
// included, as the first pass's triplets make it.
SparseMatrix planned_pattern(const DofMap& map, const AssemblyBlocks& blocks);

// A contiguous range [first, end) of the free DOFs: the columns of K_ff (and rows of K_fp) one
// process of a distributed solve owns. The default is every free DOF.
struct OwnedColumns {
  int first = 0;
  int end = std::numeric_limits<int>::max();
  bool contains(int j) const { return j >= first && j < end; }
  bool all() const { return first == 0 && end == std::numeric_limits<int>::max(); }
};

// planned_pattern's pattern with only the columns in `owned` (those of every block that reaches
// one of them: their rows may lie outside); the other columns empty. Each column is the one
// planned_pattern(map, blocks) makes.
SparseMatrix planned_pattern(const DofMap& map, const AssemblyBlocks& blocks, OwnedColumns owned);

class SystemAssembler {
 public:
  explicit SystemAssembler(const DofMap& map) : map_(&map) {}
  // A single assembly (linear static): end() builds the matrices from the triplets without the
  // value positions a later pass would reuse (they cost as much again as setFromTriplets at 2e4
  // DOFs). A later pass then starts from triplets again: slower, still correct.
  enum class Passes { Many, One };
  SystemAssembler(const DofMap& map, Passes passes) : map_(&map), one_pass_(passes == Passes::One) {}

  // Starts an assembly pass; zeroes the values once the pattern is known.
  void begin();
  // Before the first pass: about how many matrix entries it adds (an upper bound is good: room
  // reserved and not written costs no memory). Its triplets then grow in place, in huge pages.
  void expect(std::size_t entries);
  // Adds a symmetric or unsymmetric matrix over raw DOFs.
  void add(std::span<const int> raw, const Eigen::Ref<const Eigen::MatrixXd>& K);
  // Ends the pass: on the first pass, builds the pattern.
  void end();
  // Before the first pass: K_ff's pattern, as planned_pattern(map, blocks) makes it for the blocks
  // the pass will add (in any order). The first pass then writes K_ff's values into it instead of
  // collecting triplets (K_fp, small, still comes from triplets). Adding outside the plan throws.
  void plan(SparseMatrix pattern);
  // Before the first pass: only K_ff's columns and K_fp's rows in `owned` are assembled (one
  // process's share of a distributed solve; K_ff is symmetric, so its owned columns are its owned
  // rows), the others stay empty. An add whose raw DOFs reach no owned free DOF adds nothing:
  // `reaches_owned` tells the caller so before it makes the element's matrix.
  void own(OwnedColumns owned) { owned_ = owned; }
  const OwnedColumns& owned() const { return owned_; }
  bool reaches_owned(std::span<const int> raw) const;

  const SparseMatrix& K_ff() const { return Kff_; }   // free x free
  const SparseMatrix& K_fp() const { return Kfp_; }   // free x prescribed
  // True when the next pass collects no triplets for K_ff (a pass has built the pattern, or it was planned).
  bool has_pattern() const { return built_ || planned_; }
  // Must be called when the DofMap changes structure (a new map object).
  void reset(const DofMap& map);

 private:
  // Read by Eigen's setFromTriplets directly (no copy).
  struct Triplet {
    int r, c;
    double v;
    int row() const { return r; }
    int col() const { return c; }
    double value() const { return v; }
  };
  void put(std::vector<Triplet>& trip, std::vector<int>& pos, std::size_t& k, SparseMatrix& A, int r, int c, double v);
  // The first pass into a planned K_ff: column by column, each entry found from the last one's.
  void add_planned(int n, const Eigen::Ref<const Eigen::MatrixXd>& K);
  static void build(SparseMatrix& A, int rows, int cols, const std::vector<Triplet>& trip, std::vector<int>* pos);

  const DofMap* map_;
  bool one_pass_ = false;
  bool built_ = false;
  bool planned_ = false;
  OwnedColumns owned_;
  SparseMatrix Kff_, Kfp_;
  std::vector<Triplet> tff_, tfp_;
  std::vector<int> pos_ff_, pos_fp_;
  std::size_t kff_ = 0, kfp_ = 0;
  // Scratch for one call, reused between calls (member, not static).
  std::vector<std::pair<int, double>> terms_f_;
  std::vector<int> start_f_;
  std::vector<std::pair<int, double>> terms_p_;
  std::vector<int> start_p_;
};

}  // namespace beamfea

#pragma once
// Assembly of the reduced system through a DofMap.
//
// Elements give matrices and vectors over their raw DOFs; the assembler maps them through the
// constraint transformation, raw u = T_f u_free + T_p u_prescribed:
//   K_ff += T_f,e^T K_e T_f,e      K_fp += T_f,e^T K_e T_p,e
// The first assembly builds the CSC pattern from triplets; later assemblies with the same
// sequence of calls write straight into the values (the pattern, and hence the symbolic
// factorisation, is reused).
#include <Eigen/SparseCore>
#include <span>
#include <vector>

#include "core/dof_map.hpp"

namespace beamfea {

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

  const SparseMatrix& K_ff() const { return Kff_; }   // free x free
  const SparseMatrix& K_fp() const { return Kfp_; }   // free x prescribed
  bool has_pattern() const { return built_; }
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
  static void build(SparseMatrix& A, int rows, int cols, const std::vector<Triplet>& trip, std::vector<int>* pos);

  const DofMap* map_;
  bool one_pass_ = false;
  bool built_ = false;
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

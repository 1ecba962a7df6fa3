#pragma once
// Fill-reducing orderings of a large stiffness matrix computed on its compressed graph: NESDIS and
// METIS, both analysed, the one whose factor has fewer nonzeros kept (solvers/sparse_factor.cpp,
// from kOrderedMinDofs to kNesdisTrialMaxDofs).
//
// The DOFs of a node share one sparsity pattern: the graph of a frame's stiffness matrix is its
// node graph with every vertex repeated (six times; fewer at a released or eliminated DOF).
// Consecutive columns whose patterns (diagonal included) are equal are merged into one vertex (a
// "supervariable": Ashcraft, "Compressed graphs and the minimum degree algorithm", SIAM J. Sci.
// Comput. 16 (1995); George & Liu, SIAM Review 31 (1989)), CHOLMOD's nested dissection (NESDIS:
// METIS node bisections, constrained minimum degree on the parts; cholmod_nested_dissection) orders
// that graph, and each vertex is expanded back into its columns, in their order. On the compressed
// graph NESDIS costs about what METIS_NodeND costs on the whole one (which compresses internally);
// neither ordering wins on every frame (docs/performance.md, "Orderings").
#include <cholmod.h>

#include <vector>

#include "core/dof_map.hpp"

namespace beamfea {

// `lower`: the lower triangle of a symmetric matrix, compressed, rows sorted within each column (as
// CHOLMOD reads it). Uses `common` for CHOLMOD's calls, with the parameters of its method[0]
// (cholmod_defaults' nd_small, prune_dense, nd_camd ...). Empty when CHOLMOD cannot make the
// ordering (out of memory, METIS's size limits): the caller then orders as it would without it.
std::vector<int> nested_dissection_by_supervariables(const SparseMatrix& lower, cholmod_common& common);

// Both orderings of the compressed graph, for the analysis to keep the better one: NESDIS as
// above, and METIS (cholmod_metis: METIS_NodeND) on the same graph instead of CHOLMOD's METIS on
// the whole one, which first builds the graph of all the DOFs and has METIS compress it again
// (at 21,504 DOFs the analysis 0.96x, paired runs). Its vertices are unweighted, so its fill is
// not quite METIS's on the whole graph (3-6 % more on the frames of docs/performance.md,
// "Orderings"); NESDIS was kept on all of them. Either is empty when CHOLMOD could not make it.
// Each comes with the number of nonzeros of the factor it gives (factor_nonzeros below), so that
// only the better one need be analysed by CHOLMOD.
struct SupervariableOrderings {
  std::vector<int> nesdis, metis;
  double lnz_nesdis = 0.0, lnz_metis = 0.0;
};
SupervariableOrderings orderings_by_supervariables(const SparseMatrix& lower, cholmod_common& common);

// The number of nonzeros of the Cholesky factor L (diagonal included, before any amalgamation:
// CHOLMOD's Common->lnz after cholmod_analyze) of the symmetric matrix whose compressed graph is
// `graph` (strictly lower pattern, a vertex per run of `first`) eliminated in the order `group_perm`
// (new -> old), each vertex's run of columns kept together and in order. The columns of a run are
// indistinguishable (equal patterns, diagonal included), so each has the structure of its run's
// vertex expanded: the run's later columns and the columns of every vertex in the vertex's column of
// the compressed factor (George & Liu, SIAM Review 31 (1989), section 6). That column's weight is
// counted over the compressed factor's row subtrees (Liu, SIAM J. Matrix Anal. Appl. 11 (1990),
// section 3), in time proportional to the compressed factor's nonzeros, without CHOLMOD's analysis of
// the whole matrix.
double factor_nonzeros(const cholmod_sparse& graph, const std::vector<int>& first, const std::vector<int>& group_perm);

// The consecutive runs of columns of equal pattern (diagonal included) of the symmetric matrix
// whose lower triangle is `lower`: run g is columns first[g] .. first[g + 1] - 1 (first.back() = n).
std::vector<int> supervariable_starts(const SparseMatrix& lower);

}  // namespace beamfea

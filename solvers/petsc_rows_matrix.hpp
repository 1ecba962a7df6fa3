#pragma once
// PETSc's AIJ matrix of one process's rows of a symmetric Eigen matrix, shared by the linear solver
// (solvers/petsc_solver.cpp) and the eigen-solver (solvers/slepc_eigen.cpp). Private to solvers/:
// it names PETSc's types, which solvers/petsc_solver.hpp keeps out of its callers.
#include <petscmat.h>

#include <vector>

#include "core/dof_map.hpp"
#include "solvers/petsc_solver.hpp"

namespace beamfea {

// Turns a PETSc error code into the caller's exception (`what`: the call that failed).
using PetscCheck = void (*)(PetscErrorCode code, const char* what);

// The rows `rows` of A (n x n, compressed, symmetric: its CSC arrays of those columns are the CSR
// arrays of those rows, with global column indices) as an AIJ matrix on `comm`, copied: MATSEQAIJ on
// one process, MATMPIAIJ by rows on several; marked symmetric, and with the block size when above 1.
// `out` receives the matrix as soon as it exists, so that the caller's owner destroys it should a
// later call fail.
inline void symmetric_rows_aij(MPI_Comm comm, const SparseMatrix& A,
                               ProcessRows rows, PetscInt block_size, PetscCheck check, Mat& out) {
  const auto n = static_cast<PetscInt>(A.rows());
  const auto first = static_cast<PetscInt>(rows.first), local = static_cast<PetscInt>(rows.count);
  const int* outer = A.outerIndexPtr();
  std::vector<PetscInt> row_starts(static_cast<std::size_t>(local) + 1);
  for (PetscInt k = 0; k <= local; ++k) row_starts[static_cast<std::size_t>(k)] = outer[first + k] - outer[first];
  const PetscInt* cols = A.innerIndexPtr() + outer[first];
  const PetscScalar* vals = A.valuePtr() + outer[first];
  check(MatCreate(comm, &out), "MatCreate");
  check(MatSetSizes(out, local, local, n, n), "MatSetSizes");
  check(MatSetType(out, MATAIJ), "MatSetType");  // MATSEQAIJ on one process, MATMPIAIJ on several
  if (block_size > 1) check(MatSetBlockSize(out, block_size), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocationCSR(out, row_starts.data(), cols, vals), "MatSeqAIJSetPreallocationCSR");
  check(MatMPIAIJSetPreallocationCSR(out, row_starts.data(), cols, vals), "MatMPIAIJSetPreallocationCSR");
  check(MatSetOption(out, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
}

}  // namespace beamfea

// A sparse LU factorisation by MUMPS, through PETSc, kept for many solves.
//
// deal.II 9.4's PETScWrappers::SparseDirectMUMPS factorises anew on every
// solve. The solid's Newton solves need the opposite: one factorisation of a
// tangent, then many right-hand sides (fem/solid_statics.h, modified
// Newton). This holds a copy of the matrix (so the caller may reassemble its
// own) and a PETSc KSP of type preonly with an LU preconditioner by MUMPS;
// PETSc factorises in KSPSetUp and back-substitutes in every KSPSolve.
#pragma once

#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <petscksp.h>

namespace beamslider
{
  class KeptFactorisation
  {
  public:
    explicit KeptFactorisation(MPI_Comm communicator);
    ~KeptFactorisation();
    KeptFactorisation(const KeptFactorisation &)            = delete;
    KeptFactorisation &operator=(const KeptFactorisation &) = delete;

    // Copies A and factorises the copy (replacing an earlier one). Throws
    // std::runtime_error with PETSc's error code if MUMPS fails (a singular
    // matrix).
    void factorise(const dealii::PETScWrappers::MPI::SparseMatrix &A);
    bool factorised() const { return matrix != nullptr; }

    // x = A⁻¹ b with the kept factors (x and b distinct, laid out as A).
    void solve(dealii::PETScWrappers::MPI::Vector &x, const dealii::PETScWrappers::MPI::Vector &b) const;

    unsigned int n_factorisations() const { return factorisations; }
    unsigned int n_solves() const { return solves; }

  private:
    MPI_Comm communicator;
    KSP ksp    = nullptr;
    Mat matrix = nullptr;
    unsigned int factorisations = 0;
    mutable unsigned int solves = 0;
  };
} // namespace beamslider

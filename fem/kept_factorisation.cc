#include "fem/kept_factorisation.h"

#include <stdexcept>
#include <string>

namespace beamslider
{
  namespace
  {
    void check(const PetscErrorCode code, const char *call)
    {
      if (code != 0)
        throw std::runtime_error(std::string("PETSc/MUMPS: ") + call + " failed with PETSc error code " +
                                 std::to_string(code) +
                                 (code == PETSC_ERR_MAT_LU_ZRPVT ? " (zero pivot: a singular tangent)" : ""));
    }
  } // namespace

  KeptFactorisation::KeptFactorisation(const MPI_Comm communicator)
    : communicator(communicator)
  {}

  KeptFactorisation::~KeptFactorisation()
  {
    // Errors cannot be reported from here; PETSc prints its own.
    if (ksp)
      KSPDestroy(&ksp);
    if (matrix)
      MatDestroy(&matrix);
  }

  void KeptFactorisation::factorise(const dealii::PETScWrappers::MPI::SparseMatrix &A)
  {
    if (matrix)
      check(MatDestroy(&matrix), "MatDestroy");
    check(MatDuplicate(static_cast<Mat>(A), MAT_COPY_VALUES, &matrix), "MatDuplicate");
    if (!ksp)
      {
        check(KSPCreate(communicator, &ksp), "KSPCreate");
        check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
        PC pc;
        check(KSPGetPC(ksp, &pc), "KSPGetPC");
        check(PCSetType(pc, PCLU), "PCSetType");
        check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
        // A zero pivot is an error, not a silently wrong solve.
        check(KSPSetErrorIfNotConverged(ksp, PETSC_TRUE), "KSPSetErrorIfNotConverged");
      }
    check(KSPSetOperators(ksp, matrix, matrix), "KSPSetOperators");
    check(KSPSetUp(ksp), "KSPSetUp (the MUMPS factorisation)");
    ++factorisations;
  }

  void KeptFactorisation::solve(dealii::PETScWrappers::MPI::Vector &x,
                                const dealii::PETScWrappers::MPI::Vector &b) const
  {
    if (!matrix)
      throw std::logic_error("KeptFactorisation::solve before factorise");
    // deal.II's non-ghosted PETSc vectors hold no copy of their entries, so
    // PETSc may write into x's Vec directly.
    check(KSPSolve(ksp, static_cast<const Vec &>(b), static_cast<const Vec &>(x)),
          "KSPSolve (MUMPS back-substitution)");
    ++solves;
  }
} // namespace beamslider

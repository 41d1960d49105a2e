// The lowest eigenpairs of K φ = λ M φ by SLEPc: Krylov–Schur on the
// shift-and-invert transformation about σ = 0, the one way the beam's large
// meshes (fem/fe_modes.cc) and the solid (fem/solid_modes.cc) solve their
// eigenproblems.
//
// It stops after the linear solve in progress when SIGINT or SIGTERM arrives,
// on every rank together (fem/mpi_interruption.h), by throwing Interrupted;
// the factorisation of K − σM before the first iteration runs to its end.
#pragma once

#include <deal.II/lac/petsc_matrix_base.h>
#include <deal.II/lac/petsc_vector.h>

#include <string>
#include <vector>

namespace beamslider
{
  struct ShiftInvertSettings
  {
    // On SLEPc's relative residual ‖Kφ − λMφ‖/(|λ| ‖φ‖).
    double tolerance            = 1e-12;
    unsigned int max_iterations = 1000;
    // Factorise K − σM with MUMPS (distributed, any number of ranks)
    // instead of PETSc's own LU (one rank only). Chosen through PETSc's
    // options database: deal.II 9.4.1's set_solver with its MUMPS wrapper
    // crashes.
    bool mumps = false;
    // What is being solved, for the message of a failure.
    std::string what = "eigenproblem";
  };

  // The `n` lowest eigenpairs into `eigenvalues` (unordered, as SLEPc gives
  // them) and `vectors`, which the caller sizes (n vectors of K's layout).
  // Returns the number of Krylov–Schur iterations. Throws std::runtime_error naming
  // settings.what when SLEPc fails, Interrupted when stopped by a signal.
  unsigned int lowest_eigenpairs(const dealii::PETScWrappers::MatrixBase &K,
                                 const dealii::PETScWrappers::MatrixBase &M, unsigned int n,
                                 const ShiftInvertSettings &settings, std::vector<double> &eigenvalues,
                                 std::vector<dealii::PETScWrappers::MPI::Vector> &vectors);
} // namespace beamslider

#include "fem/fe_modes.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/slepc_solver.h>
#include <deal.II/lac/slepc_spectral_transformation.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_matrix.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace beamslider
{
  using namespace dealii;

  namespace
  {
    // Copies a deal.II sparse matrix into a sequential PETSc matrix, the
    // format SLEPc works on.
    void copy_to_petsc(const SparseMatrix<double> &A, PETScWrappers::SparseMatrix &P)
    {
      std::vector<unsigned int> row_lengths(A.m());
      for (unsigned int i = 0; i < A.m(); ++i)
        row_lengths[i] = A.get_row_length(i);
      P.reinit(A.m(), A.n(), row_lengths);
      for (unsigned int i = 0; i < A.m(); ++i)
        for (auto it = A.begin(i); it != A.end(i); ++it)
          P.set(i, it->column(), it->value());
      P.compress(VectorOperation::insert);
    }
  } // namespace

  FEModes compute_bending_modes(const FEBeam &beam, const unsigned int n_modes, const std::optional<BondedBody> &body)
  {
    const auto &constraints = beam.bending_constraints();

    SparseMatrix<double> M, K;
    beam.assemble_mass_matrix(M, constraints);
    beam.assemble_internal_force(Vector<double>(beam.n_dofs()), nullptr, &K, constraints);
    if (body)
      beam.add_point_inertia(body->x, body->mass, body->inertia, M);

    // A constrained DoF gets a zero mass: its eigenvalue moves to infinity,
    // far from the shift, instead of polluting the low spectrum.
    for (unsigned int i = 0; i < beam.n_dofs(); ++i)
      if (constraints.is_constrained(i))
        M.set(i, i, 0.);

    const unsigned int n_free = beam.n_dofs() - constraints.n_constraints();
    AssertThrow(n_modes <= n_free,
                ExcMessage("Requested " + std::to_string(n_modes) + " modes but the mesh has only " +
                           std::to_string(n_free) + " bending DoFs: refine the mesh"));

    PETScWrappers::SparseMatrix K_petsc, M_petsc;
    copy_to_petsc(K, K_petsc);
    copy_to_petsc(M, M_petsc);

    std::vector<PETScWrappers::MPI::Vector> vectors(n_modes + 2);
    for (auto &v : vectors)
      v.reinit(MPI_COMM_SELF, beam.n_dofs(), beam.n_dofs());
    std::vector<double> eigenvalues;

    // Shift-invert about 0 with SLEPc's default solver for the spectral
    // transformation (direct LU: DESIGN.md §5 notes that MUMPS through the
    // wrapper crashes in 9.4.1).
    SolverControl control(1000, 1e-12, false, false);
    SLEPcWrappers::SolverKrylovSchur solver(control, MPI_COMM_SELF);
    SLEPcWrappers::TransformationShiftInvert shift_invert(MPI_COMM_SELF,
                                                          SLEPcWrappers::TransformationShiftInvert::AdditionalData(0.));
    solver.set_transformation(shift_invert);
    solver.set_problem_type(EPS_GHEP);
    solver.set_which_eigenpairs(EPS_TARGET_MAGNITUDE);
    solver.set_target_eigenvalue(0.);
    try
      {
        solver.solve(K_petsc, M_petsc, eigenvalues, vectors, n_modes);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        throw std::runtime_error("SLEPc eigensolver failed for the " + std::to_string(n_modes) +
                                 " lowest bending modes (" + std::to_string(beam.n_elements()) +
                                 " elements): " + info.str());
      }

    std::vector<unsigned int> order(eigenvalues.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) { return eigenvalues[a] < eigenvalues[b]; });

    FEModes modes;
    modes.eigensolver_iterations = control.last_step();
    const double L               = beam.length();
    for (unsigned int k = 0; k < n_modes; ++k)
      {
        const unsigned int i = order[k];
        AssertThrow(eigenvalues[i] > 0, ExcMessage("Non-positive eigenvalue " + std::to_string(eigenvalues[i]) +
                                                   ": the beam is not supported against rigid motion"));
        Vector<double> phi(beam.n_dofs());
        for (unsigned int j = 0; j < beam.n_dofs(); ++j)
          phi[j] = vectors[i][j];
        constraints.distribute(phi);
        phi /= std::sqrt(M.matrix_norm_square(phi));

        // Sign: ∫ φ (L - x) dx > 0, by the 8-point midpoint sum on each element.
        double moment = 0;
        const unsigned int n_samples = 8 * beam.n_elements();
        for (unsigned int s = 0; s < n_samples; ++s)
          {
            const double x = (s + 0.5) * L / n_samples;
            moment += beam.deflection(phi, x) * (L - x);
          }
        if (moment < 0)
          phi *= -1.;
        modes.omega.push_back(std::sqrt(eigenvalues[i]));
        modes.shapes.push_back(std::move(phi));
      }
    return modes;
  }
} // namespace beamslider

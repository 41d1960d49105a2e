#include "fem/fe_modes.h"

#include "fem/petsc_session.h"
#include "fem/shift_invert_eigensolver.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/sparse_matrix.h>

#include <Eigen/Eigenvalues>

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

    // The dense route needs homogeneous constraints that pin DoFs to zero
    // (the supports' w and every u): then the free DoFs carry the whole
    // problem and M restricted to them is positive definite.
    bool pins_to_zero(const AffineConstraints<double> &constraints)
    {
      for (const auto &line : constraints.get_lines())
        if (!line.entries.empty() || line.inhomogeneity != 0.)
          return false;
      return true;
    }

    bool use_dense_solver(const EigenSolverMethod method, const AffineConstraints<double> &constraints,
                          const unsigned int n_free)
    {
      switch (method)
        {
          case EigenSolverMethod::dense:
            AssertThrow(pins_to_zero(constraints),
                        ExcMessage("the dense eigensolver needs constraints that pin DoFs to zero"));
            return true;
          case EigenSolverMethod::slepc:
            return false;
          case EigenSolverMethod::automatic:
            break;
        }
      return n_free <= max_dense_eigenproblem_size && pins_to_zero(constraints);
    }

    // All eigenpairs of the free DoFs' problem at once with Eigen's
    // generalised self-adjoint solver (a Cholesky factor, then a symmetric QR
    // iteration), posed inverted: M φ = μ K φ, μ = 1/ω². A dense solver's
    // error is relative to the largest eigenvalue; inverted, that is the
    // lowest mode's (the dense analogue of shift-invert about 0): ω_1 within
    // 1e-12 instead of ε λ_max/λ_1 ≈ 5e-11 on the default mesh
    // (tests/test_fem_beam.cc against an 80-bit reference).
    // The lowest n_modes are returned as full DoF vectors, zero on the
    // constrained DoFs.
    void solve_dense(const SparseMatrix<double> &K, const SparseMatrix<double> &M,
                     const AffineConstraints<double> &constraints, const unsigned int n_modes,
                     std::vector<double> &eigenvalues, std::vector<Vector<double>> &vectors)
    {
      const FreeDofProblem free       = restrict_to_free_dofs(K, M, constraints);
      const std::vector<unsigned int> &free_dofs = free.dofs;
      const Eigen::MatrixXd &K_free = free.K, &M_free = free.M;
      const Eigen::Index n          = free_dofs.size();
      const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(M_free, K_free);
      AssertThrow(solver.info() == Eigen::Success,
                  ExcMessage("dense eigensolver failed: the stiffness matrix is not positive definite (is the beam "
                             "supported against rigid motion?)"));
      for (unsigned int k = 0; k < n_modes; ++k) // μ ascending: the lowest modes are the last
        {
          const Eigen::Index i = n - 1 - k;
          eigenvalues.push_back(1. / solver.eigenvalues()[i]);
          Vector<double> phi(K.m());
          for (Eigen::Index a = 0; a < n; ++a)
            phi[free_dofs[a]] = solver.eigenvectors()(a, i);
          vectors.push_back(std::move(phi));
        }
    }

    // Shift-invert about 0 (fem/shift_invert_eigensolver.h) on one rank, with
    // PETSc's own LU. Starts MPI/PETSc/SLEPc on first use.
    unsigned int solve_with_slepc(const FEBeam &beam, const SparseMatrix<double> &K, SparseMatrix<double> &M,
                                  const unsigned int n_modes, std::vector<double> &eigenvalues,
                                  std::vector<Vector<double>> &vectors)
    {
      require_petsc();
      // A constrained DoF gets a zero mass: its eigenvalue moves to infinity,
      // far from the shift, instead of polluting the low spectrum.
      const auto &constraints = beam.bending_constraints();
      for (unsigned int i = 0; i < beam.n_dofs(); ++i)
        if (constraints.is_constrained(i))
          M.set(i, i, 0.);

      PETScWrappers::SparseMatrix K_petsc, M_petsc;
      copy_to_petsc(K, K_petsc);
      copy_to_petsc(M, M_petsc);

      std::vector<PETScWrappers::MPI::Vector> petsc_vectors(n_modes);
      for (auto &v : petsc_vectors)
        v.reinit(MPI_COMM_SELF, beam.n_dofs(), beam.n_dofs());

      ShiftInvertSettings settings;
      settings.what = "the " + std::to_string(n_modes) + " lowest bending modes (" +
                      std::to_string(beam.n_elements()) + " elements)";
      const unsigned int iterations = lowest_eigenpairs(K_petsc, M_petsc, n_modes, settings, eigenvalues, petsc_vectors);
      for (unsigned int i = 0; i < eigenvalues.size(); ++i)
        {
          Vector<double> phi(beam.n_dofs());
          for (unsigned int j = 0; j < beam.n_dofs(); ++j)
            phi[j] = petsc_vectors[i][j];
          vectors.push_back(std::move(phi));
        }
      return iterations;
    }
  } // namespace

  FreeDofProblem restrict_to_free_dofs(const SparseMatrix<double> &K, const SparseMatrix<double> &M,
                                       const AffineConstraints<double> &constraints)
  {
    AssertThrow(pins_to_zero(constraints), ExcMessage("restrict_to_free_dofs needs constraints that pin DoFs to zero"));
    FreeDofProblem free;
    std::vector<int> &free_index = free.row_of_dof;
    free_index.assign(K.m(), -1);
    for (unsigned int i = 0; i < K.m(); ++i)
      if (!constraints.is_constrained(i))
        {
          free_index[i] = free.dofs.size();
          free.dofs.push_back(i);
        }
    const Eigen::Index n = free.dofs.size();
    free.K               = Eigen::MatrixXd::Zero(n, n);
    free.M               = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index a = 0; a < n; ++a)
      {
        for (auto it = K.begin(free.dofs[a]); it != K.end(free.dofs[a]); ++it)
          if (free_index[it->column()] >= 0)
            free.K(a, free_index[it->column()]) = it->value();
        for (auto it = M.begin(free.dofs[a]); it != M.end(free.dofs[a]); ++it)
          if (free_index[it->column()] >= 0)
            free.M(a, free_index[it->column()]) = it->value();
      }
    return free;
  }

  void fix_shape_sign(const FEBeam &beam, Vector<double> &phi)
  {
    const double L               = beam.length();
    double moment                = 0;
    const unsigned int n_samples = 8 * beam.n_elements();
    for (unsigned int s = 0; s < n_samples; ++s)
      {
        const double x = (s + 0.5) * L / n_samples;
        moment += beam.deflection(phi, x) * (L - x);
      }
    if (moment < 0)
      phi *= -1.;
  }

  FEModes compute_bending_modes(const FEBeam &beam, const unsigned int n_modes, const std::optional<BondedBody> &body,
                                const EigenSolverMethod method)
  {
    const auto &constraints = beam.bending_constraints();

    SparseMatrix<double> M, K;
    beam.assemble_mass_matrix(M, constraints);
    beam.assemble_internal_force(Vector<double>(beam.n_dofs()), nullptr, &K, constraints);
    if (body)
      beam.add_point_inertia(body->x, body->mass, body->inertia, M);

    const unsigned int n_free = beam.n_dofs() - constraints.n_constraints();
    AssertThrow(n_modes <= n_free,
                ExcMessage("Requested " + std::to_string(n_modes) + " modes but the mesh has only " +
                           std::to_string(n_free) + " bending DoFs: refine the mesh"));

    std::vector<double> eigenvalues;
    std::vector<Vector<double>> vectors;
    unsigned int iterations = 0;
    if (use_dense_solver(method, constraints, n_free))
      solve_dense(K, M, constraints, n_modes, eigenvalues, vectors);
    else
      iterations = solve_with_slepc(beam, K, M, n_modes, eigenvalues, vectors);

    std::vector<unsigned int> order(eigenvalues.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) { return eigenvalues[a] < eigenvalues[b]; });

    FEModes modes;
    modes.eigensolver_iterations = iterations;
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

        fix_shape_sign(beam, phi);
        modes.omega.push_back(std::sqrt(eigenvalues[i]));
        modes.shapes.push_back(std::move(phi));
      }
    return modes;
  }
} // namespace beamslider

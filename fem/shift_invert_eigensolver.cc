#include "fem/shift_invert_eigensolver.h"

#include "contact/interruption.h"
#include "fem/mpi_interruption.h"

#include <deal.II/lac/slepc_solver.h>
#include <deal.II/lac/slepc_spectral_transformation.h>

#include <petscsys.h>

#include <sstream>

namespace beamslider
{
  using namespace dealii;

  namespace
  {
    // Krylov–Schur that also ends (unconverged) when a signal arrived: SLEPc
    // calls the stopping test once per iteration on every rank, so the
    // collective check inside is safe.
    class InterruptibleKrylovSchur : public SLEPcWrappers::SolverKrylovSchur
    {
    public:
      InterruptibleKrylovSchur(SolverControl &control, const MPI_Comm comm)
        : SolverKrylovSchur(control, comm)
      {
        const PetscErrorCode ierr = EPSSetStoppingTestFunction(eps, &stop, nullptr, nullptr);
        AssertThrow(ierr == 0, ExcMessage("EPSSetStoppingTestFunction failed"));
      }

    private:
      static PetscErrorCode stop(EPS eps, PetscInt its, PetscInt max_it, PetscInt nconv, PetscInt nev,
                                 EPSConvergedReason *reason, void *context)
      {
        const PetscErrorCode ierr = EPSStoppingBasic(eps, its, max_it, nconv, nev, reason, context);
        if (ierr != 0 || *reason != EPS_CONVERGED_ITERATING)
          return ierr;
        MPI_Comm comm;
        PetscObjectGetComm(reinterpret_cast<PetscObject>(eps), &comm);
        if (agreed_interruption_signal(comm) != 0)
          *reason = EPS_DIVERGED_ITS;
        return 0;
      }
    };
  } // namespace

  unsigned int lowest_eigenpairs(const PETScWrappers::MatrixBase &K, const PETScWrappers::MatrixBase &M,
                                 const unsigned int n, const ShiftInvertSettings &settings,
                                 std::vector<double> &eigenvalues, std::vector<PETScWrappers::MPI::Vector> &vectors)
  {
    const MPI_Comm comm = K.get_mpi_communicator();
    stop_if_interrupted(comm); // a signal during the assembly
    if (settings.mumps)
      {
        PetscOptionsSetValue(nullptr, "-st_ksp_type", "preonly");
        PetscOptionsSetValue(nullptr, "-st_pc_type", "lu");
        PetscOptionsSetValue(nullptr, "-st_pc_factor_mat_solver_type", "mumps");
      }
    SolverControl control(settings.max_iterations, settings.tolerance, false, false);
    InterruptibleKrylovSchur solver(control, comm);
    SLEPcWrappers::TransformationShiftInvert shift_invert(comm,
                                                          SLEPcWrappers::TransformationShiftInvert::AdditionalData(0.));
    solver.set_transformation(shift_invert);
    solver.set_problem_type(EPS_GHEP);
    solver.set_which_eigenpairs(EPS_TARGET_MAGNITUDE);
    solver.set_target_eigenvalue(0.);
    try
      {
        solver.solve(K, M, eigenvalues, vectors, n);
      }
    catch (const ExceptionBase &e)
      {
        // Stopped by the test above (which gave every rank the signal): not
        // a failure. A local check: a rank that failed alone must not wait
        // for the others in a collective.
        stop_if_interrupted();
        std::ostringstream info;
        e.print_info(info);
        throw std::runtime_error("SLEPc eigensolver failed for " + settings.what + ": " + info.str());
      }
    vectors.resize(eigenvalues.size());
    return control.last_step();
  }
} // namespace beamslider

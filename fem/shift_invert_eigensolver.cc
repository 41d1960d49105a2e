#include "fem/shift_invert_eigensolver.h"

#include "numerics/stop_request.h"
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
    // While it lives, PETSc errors print nothing: the first message is kept
    // for the exception that reports the failure once. It also silences the
    // complaint of EPSDestroy about a solve stopped half-way.
    class PetscMessageCatcher
    {
    public:
      PetscMessageCatcher() { PetscPushErrorHandler(&remember, &first); }
      ~PetscMessageCatcher() { PetscPopErrorHandler(); }
      PetscMessageCatcher(const PetscMessageCatcher &) = delete;
      PetscMessageCatcher &operator=(const PetscMessageCatcher &) = delete;

      std::string first;

    private:
      static PetscErrorCode remember(MPI_Comm, int, const char *, const char *, const PetscErrorCode error,
                                     const PetscErrorType type, const char *message, void *context)
      {
        auto &first = *static_cast<std::string *>(context);
        if (type == PETSC_ERROR_INITIAL && first.empty() && message != nullptr)
          first = message;
        return error;
      }
    };

    // Krylov–Schur that stops when a signal arrived, after the solve with
    // K − σM in progress: SLEPc applies the operator on every rank together,
    // so the collective check after each solve is safe, and a Krylov–Schur
    // restart (36 solves for 18 modes) is too long to wait for.
    class InterruptibleKrylovSchur : public SLEPcWrappers::SolverKrylovSchur
    {
    public:
      InterruptibleKrylovSchur(SolverControl &control, const MPI_Comm comm, const PetscMessageCatcher &petsc)
        : SolverKrylovSchur(control, comm)
        , comm(comm)
        , petsc(petsc)
      {}

      // deal.II's solve() without its last loop, which computes the
      // residual of every converged pair (often twice as many as asked) and
      // cannot be interrupted: at 143,055 DoFs it went on for seconds after
      // Ctrl-C. Returns the number of Krylov–Schur iterations.
      unsigned int solve_lowest(const PETScWrappers::MatrixBase &K, const PETScWrappers::MatrixBase &M,
                                const unsigned int n, std::vector<double> &eigenvalues,
                                std::vector<PETScWrappers::MPI::Vector> &vectors)
      {
        set_matrices(K, M);
        check(EPSSetDimensions(eps, n, PETSC_DEFAULT, PETSC_DEFAULT), "EPSSetDimensions");
        check(EPSSetTolerances(eps, solver_control.tolerance(), solver_control.max_steps()), "EPSSetTolerances");
        check(EPSSetFromOptions(eps), "EPSSetFromOptions");
        ST st;
        KSP ksp;
        check(EPSGetST(eps, &st), "EPSGetST");
        check(STGetKSP(st, &ksp), "STGetKSP");
        check(KSPSetPostSolve(ksp, &stop_if_signalled, nullptr), "KSPSetPostSolve");

        const PetscErrorCode solved = EPSSolve(eps);
        if (solved != 0) // also a stop by stop_if_signalled, which the caller tells apart
          throw std::runtime_error("EPSSolve failed (PETSc error " + std::to_string(solved) +
                                     (petsc.first.empty() ? "" : ": " + petsc.first) + ")");

        PetscInt iterations = 0, converged = 0;
        EPSConvergedReason reason;
        check(EPSGetIterationNumber(eps, &iterations), "EPSGetIterationNumber");
        check(EPSGetConverged(eps, &converged), "EPSGetConverged");
        check(EPSGetConvergedReason(eps, &reason), "EPSGetConvergedReason");
        if (converged < static_cast<PetscInt>(n))
          throw std::runtime_error(std::to_string(converged) + " of " + std::to_string(n) +
                                   " eigenpairs converged in " + std::to_string(iterations) + " iterations (" +
                                   EPSConvergedReasons[reason] + ")");
        if (vectors.size() < n)
          throw std::logic_error("lowest_eigenpairs needs " + std::to_string(n) + " vectors of K's layout");
        eigenvalues.resize(n);
        for (unsigned int i = 0; i < n; ++i)
          {
            stop_if_interrupted(comm);
            PetscScalar real = 0, imaginary = 0;
            check(EPSGetEigenpair(eps, i, &real, &imaginary, vectors[i], nullptr), "EPSGetEigenpair");
            eigenvalues[i] = PetscRealPart(real);
          }
        return iterations;
      }

    private:
      const MPI_Comm comm;
      const PetscMessageCatcher &petsc;

      static void check(const PetscErrorCode ierr, const char *call)
      {
        if (ierr != 0)
          throw std::runtime_error(std::string(call) + " failed (PETSc error " + std::to_string(ierr) + ")");
      }

      static PetscErrorCode stop_if_signalled(KSP ksp, Vec, Vec, void *)
      {
        MPI_Comm comm;
        PetscObjectGetComm(reinterpret_cast<PetscObject>(ksp), &comm);
        return agreed_interruption_signal(comm) != 0 ? PETSC_ERR_USER : 0;
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
    const PetscMessageCatcher petsc; // outlives the solver
    InterruptibleKrylovSchur solver(control, comm, petsc);
    SLEPcWrappers::TransformationShiftInvert shift_invert(comm,
                                                          SLEPcWrappers::TransformationShiftInvert::AdditionalData(0.));
    solver.set_transformation(shift_invert);
    solver.set_problem_type(EPS_GHEP);
    solver.set_which_eigenpairs(EPS_TARGET_MAGNITUDE);
    solver.set_target_eigenvalue(0.);
    // A failure on one rank alone must not wait for the others in a
    // collective: the checks on the way out are local (after a stop by a
    // signal every rank has it).
    try
      {
        return solver.solve_lowest(K, M, n, eigenvalues, vectors);
      }
    catch (const ExceptionBase &e)
      {
        stop_if_interrupted();
        std::ostringstream info;
        e.print_info(info);
        throw std::runtime_error("SLEPc eigensolver failed for " + settings.what + ": " + info.str());
      }
    catch (const Interrupted &)
      {
        throw;
      }
    catch (const std::runtime_error &e)
      {
        stop_if_interrupted();
        throw std::runtime_error("SLEPc eigensolver failed for " + settings.what + ": " + e.what());
      }
  }
} // namespace beamslider

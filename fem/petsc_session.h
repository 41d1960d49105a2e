// MPI, PETSc and SLEPc, started when first needed.
//
// Starting Open MPI as a singleton (no mpirun) forks its run-time daemon and
// loads its components: about 0.6 s on this project's machines, longer than
// the set-up of a whole reduced-order run. Only the SLEPc eigensolver (large
// meshes, fem/fe_modes.cc) needs it, so the program does not start MPI in
// main(); require_petsc() does, once per process, the first time it is
// called (or an mpirun-launched command's MpiSession, at its start). MPI,
// PETSc and SLEPc are finalised at program exit. A program that started them
// itself (the test mains with deal.II's MPI_InitFinalize) is left alone.
#pragma once

namespace beamslider
{
  // Thread-safe; cheap after the first call.
  void require_petsc();

  // Whether MPI has been started (by require_petsc or by the program).
  bool mpi_started();
} // namespace beamslider

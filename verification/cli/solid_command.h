// What the sub-commands on a solid scene share (command_*_solid.cc): MPI
// for the command's lifetime, the dimension chosen from the scene, and the
// output folder prepared by rank 0 and known to every rank.
#pragma once

#include "output/collective_failure.h"
#include "fem/petsc_session.h"
#include "scene/scene.h"
#include "verification/cli/commands.h"
#include "runtime/mpi_cells.h"

#include <deal.II/base/mpi.h>

#include <type_traits>

namespace beamslider
{
  // Runs run(std::integral_constant<int, dim>) for the scene's solid, with
  // MPI started (by mpirun's launch, or as a singleton).
  template <typename Run>
  int run_on_solid(const Scene &scene, const Run &run)
  {
    MpiSession mpi(launched_by_mpi_launcher());
    require_petsc();
    return scene.solid.dimension() == 3 ? run(std::integral_constant<int, 3>{}) : run(std::integral_constant<int, 2>{});
  }

  // The command's output folder: prepared (parameters.prm, run.txt, ...) by
  // rank 0 alone, its path broadcast to every rank; if rank 0 cannot
  // prepare it (in use, not writable), every rank throws its error.
  inline std::string solid_output_dir(const CommonOptions &common, const Scene &scene, const std::string &command)
  {
    std::string dir;
    fail_together(MPI_COMM_WORLD, [&] {
      if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        dir = prepare_output_dir(common, scene, command);
    });
    return dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, dir, 0);
  }
} // namespace beamslider

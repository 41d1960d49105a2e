// `beamslider sweep`: not implemented yet (placeholder so the CLI links).
#include "meshes/scene.h"
#include "verification/commands.h"

namespace beamslider
{
  int run_sweep(const CommonOptions &, const SweepOptions &)
  {
    throw std::runtime_error("beamslider sweep is not implemented yet");
  }
} // namespace beamslider

// `beamslider simulate`: not implemented yet (placeholder so the CLI links).
#include "meshes/scene.h"
#include "verification/commands.h"

namespace beamslider
{
  int run_simulate(const CommonOptions &, const SimulateOptions &)
  {
    throw std::runtime_error("beamslider simulate is not implemented yet");
  }
} // namespace beamslider

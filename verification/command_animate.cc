// `beamslider animate`: not implemented yet (placeholder so the CLI links).
#include "meshes/scene.h"
#include "verification/commands.h"

namespace beamslider
{
  int run_animate(const CommonOptions &, const AnimateOptions &)
  {
    throw std::runtime_error("beamslider animate is not implemented yet");
  }
} // namespace beamslider

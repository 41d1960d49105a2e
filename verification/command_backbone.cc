// `beamslider backbone`: not implemented yet (placeholder so the CLI links).
#include "meshes/scene.h"
#include "verification/commands.h"

namespace beamslider
{
  int run_backbone(const CommonOptions &, const BackboneOptions &)
  {
    throw std::runtime_error("beamslider backbone is not implemented yet");
  }
} // namespace beamslider

// `beamslider coefficients`: not implemented yet (placeholder so the CLI links).
#include "meshes/scene.h"
#include "verification/commands.h"

namespace beamslider
{
  int run_coefficients(const CommonOptions &, const CoefficientsOptions &)
  {
    throw std::runtime_error("beamslider coefficients is not implemented yet");
  }
} // namespace beamslider

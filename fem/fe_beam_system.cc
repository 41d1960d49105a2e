#include "fem/fe_beam_system.h"

#include <stdexcept>

namespace beamslider
{
  std::unique_ptr<BeamSystem> make_fe_beam_system(const Scene &)
  {
    throw std::runtime_error("the FE beam with the slider (--model fe) is not implemented yet");
  }
} // namespace beamslider

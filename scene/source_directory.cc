#include "scene/source_directory.h"

namespace beamslider
{
  std::string source_directory() { return BEAMSLIDER_SOURCE_DIR; }
} // namespace beamslider

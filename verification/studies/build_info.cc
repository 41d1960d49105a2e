#include "verification/studies/build_info.h"

#include "build_info_values.h" // generated: version, revision, instruction set

namespace beamslider
{
  const BuildInfo &build_info()
  {
    static const BuildInfo info{BEAMSLIDER_VERSION_STRING, BEAMSLIDER_REVISION, BEAMSLIDER_BUILT_FOR};
    return info;
  }

  std::string build_revision() { return "beamslider " + build_info().version + " " + build_info().revision; }
} // namespace beamslider

// Verification section placeholder: not implemented yet.
#include "verification/report.h"

namespace beamslider
{
  void add_backbone_section(Report &report, const Scene &, bool)
  {
    report.text << "## (section backbone: not implemented yet)\n\n";
  }
} // namespace beamslider

// Verification section placeholder: not implemented yet.
#include "verification/report.h"

namespace beamslider
{
  void add_coefficient_section(Report &report, const Scene &, bool)
  {
    report.text << "## (section coefficient: not implemented yet)\n\n";
  }
} // namespace beamslider

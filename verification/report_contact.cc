// Verification section placeholder: not implemented yet.
#include "verification/report.h"

namespace beamslider
{
  void add_contact_section(Report &report, const Scene &, bool)
  {
    report.text << "## (section contact: not implemented yet)\n\n";
  }
} // namespace beamslider

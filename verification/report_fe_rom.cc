// Verification section placeholder: not implemented yet.
#include "verification/report.h"

namespace beamslider
{
  void add_fe_rom_section(Report &report, const Scene &, bool)
  {
    report.text << "## (section fe_rom: not implemented yet)\n\n";
  }
} // namespace beamslider

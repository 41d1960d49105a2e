// The verification report: a Markdown file assembled from sections, each
// written by one study (frequencies, coefficients, backbones, contact cases,
// ...) together with its CSV files and PNG charts in the same folder.
#pragma once

#include "meshes/scene.h"

#include <sstream>
#include <string>

namespace beamslider
{
  struct Report
  {
    std::string dir;          // output folder (report.md, CSV, PNG)
    std::ostringstream text;  // Markdown
  };

  // Section 1: linear frequencies. FE against the clamped–clamped and the
  // spring-supported characteristic equations on refined meshes (error and
  // observed order per mode), the bonded slider against seed Eq. 5, and the
  // choice of the default mesh.
  void add_frequency_section(Report &report, const Scene &scene);
} // namespace beamslider

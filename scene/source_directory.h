// Where the project's sources are: the scenes in meshes/ and the chart
// scripts in scripts/ are found there when a path is not given.
//
// The path is compiled into one file only (source_directory.cc), so the rest
// of the project compiles to the same object code whichever folder it is
// built from (ccache hits across checkouts).
#pragma once

#include <string>

namespace beamslider
{
  std::string source_directory();
} // namespace beamslider

// A file's whole text for a test's comparison. A file that cannot be read
// fails the calling test: otherwise two runs that both failed to write their
// output would compare equal, and a check that a text is absent would pass.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace beamslider::testing
{
  inline std::string read_file(const std::filesystem::path &path)
  {
    std::ifstream in(path, std::ios::binary);
    if (!in)
      {
        ADD_FAILURE() << "cannot read " << path;
        return {};
      }
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
} // namespace beamslider::testing

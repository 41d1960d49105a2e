// A fresh, empty scratch folder for one test, for every kind of test (the
// end-to-end helpers of cli_runner.h need the built executable; this does not).
#pragma once

#include <filesystem>
#include <string>
#include <unistd.h>

namespace beamslider::testing
{
  // <temp>/beamslider_test_<name>_<pid>, emptied and created.
  inline std::filesystem::path fresh_folder(const std::string &name)
  {
    const auto dir = std::filesystem::temp_directory_path() / ("beamslider_test_" + name + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
  }
} // namespace beamslider::testing

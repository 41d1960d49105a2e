#include "runtime/build_info.h"

#include "build_info_values.h" // generated: version, revision, instruction set

#include <dlfcn.h>
#include <sys/stat.h>

#include <string>

namespace beamslider
{
  const BuildInfo &build_info()
  {
    static const BuildInfo info{BEAMSLIDER_VERSION_STRING, BEAMSLIDER_REVISION, BEAMSLIDER_BUILT_FOR};
    return info;
  }

  std::string build_revision() { return "beamslider " + build_info().version + " " + build_info().revision; }

  namespace
  {
    std::string read_executable_identity()
    {
      // The file this code was loaded from: the beamslider executable, a test
      // program or the Python module (not the Python interpreter).
      // (The main program may be named by an empty or relative name: then
      // /proc/self/exe.)
      Dl_info info{};
      struct stat st{};
      const bool named = dladdr(reinterpret_cast<void *>(&read_executable_identity), &info) != 0 && info.dli_fname &&
                         info.dli_fname[0] != '\0' && ::stat(info.dli_fname, &st) == 0;
      if (!named && ::stat("/proc/self/exe", &st) != 0)
        return "unknown";
      const long long modified_ns = static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
      return std::to_string(static_cast<long long>(st.st_size)) + " bytes, modified " + std::to_string(modified_ns);
    }
  } // namespace

  std::string executable_identity()
  {
    // Read once: a rebuild while this process runs must not lend the new
    // file's identity to this build's results.
    static const std::string identity = read_executable_identity();
    return identity;
  }
} // namespace beamslider

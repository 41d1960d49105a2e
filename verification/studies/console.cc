// The switchable console stream, see console.h.
#include "verification/studies/console.h"

#include <iostream>

namespace beamslider
{
  namespace
  {
    bool quiet_ = false;

    // An ostream without a buffer sets badbit on output and writes nothing.
    std::ostream &discarding_stream()
    {
      static std::ostream discard(nullptr);
      return discard;
    }
  } // namespace

  std::ostream &console() { return quiet_ ? discarding_stream() : std::cout; }

  void set_quiet(const bool quiet) { quiet_ = quiet; }
} // namespace beamslider

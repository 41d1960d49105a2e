// The explanation of a deal.II exception on one line, without the banner of
// source files and line numbers that means nothing to a user: what an
// InputError quotes when deal.II refuses a file or a value.
#pragma once

#include <string>

namespace dealii
{
  class ExceptionBase;
}

namespace beamslider
{
  std::string deal_ii_message(const dealii::ExceptionBase &e);
} // namespace beamslider

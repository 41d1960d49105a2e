// Command-line checks that say what is wrong in one line.
//
// CLI11's stock range checks let NaN through (every comparison with NaN is
// false) and print an open bound as DBL_MAX's 309 digits; these reject
// non-finite numbers and name the allowed range in short form. A parse error
// becomes one line (describe_parse_error), with the closest sub-command when
// the user mistyped one.
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace beamslider
{
  enum class Bound
  {
    open,
    closed
  };

  namespace cli_detail
  {
    inline std::string number(const double x)
    {
      std::ostringstream s;
      s << x;
      return s.str();
    }

    // Parses the whole string as a double; false for trailing junk.
    inline bool parse_double(const std::string &text, double &value)
    {
      const char *begin = text.c_str();
      char *end         = nullptr;
      value             = std::strtod(begin, &end);
      return end != begin && *end == '\0';
    }
  } // namespace cli_detail

  // A finite number in [lo, hi] (or with open ends); hi = +inf for no upper bound.
  inline CLI::Validator finite_in(const double lo, const double hi, const Bound lo_bound = Bound::closed,
                                  const Bound hi_bound = Bound::closed)
  {
    using cli_detail::number;
    const std::string range = (lo_bound == Bound::open ? "(" : "[") + number(lo) + ", " +
                              (std::isinf(hi) ? std::string("inf)") : number(hi) + (hi_bound == Bound::open ? ")" : "]"));
    return CLI::Validator(
      [=](std::string &text) -> std::string {
        double x = 0;
        if (!cli_detail::parse_double(text, x))
          return "'" + text + "' is not a number";
        if (!std::isfinite(x))
          return "'" + text + "' is not a finite number; allowed: " + range;
        const bool above = lo_bound == Bound::open ? x > lo : x >= lo;
        const bool below = std::isinf(hi) || (hi_bound == Bound::open ? x < hi : x <= hi);
        if (!above || !below)
          return number(x) + " is outside the allowed range " + range;
        return {};
      },
      "in " + range);
  }

  inline CLI::Validator finite_positive()
  {
    return finite_in(0., std::numeric_limits<double>::infinity(), Bound::open, Bound::open);
  }

  inline CLI::Validator finite_non_negative()
  {
    return finite_in(0., std::numeric_limits<double>::infinity(), Bound::closed, Bound::open);
  }

  // A finite number other than zero (a load of either sign).
  inline CLI::Validator finite_nonzero()
  {
    return CLI::Validator(
      [](std::string &text) -> std::string {
        double x = 0;
        if (!cli_detail::parse_double(text, x))
          return "'" + text + "' is not a number";
        if (!std::isfinite(x) || x == 0)
          return "'" + text + "' is not allowed: a finite number other than 0";
        return {};
      },
      "finite, non-zero");
  }

  // A whole number in [lo, hi].
  inline CLI::Validator integer_in(const long lo, const long hi)
  {
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    return CLI::Validator(
      [=](std::string &text) -> std::string {
        const char *begin = text.c_str();
        char *end         = nullptr;
        const long x      = std::strtol(begin, &end, 10);
        if (end == begin || *end != '\0')
          return "'" + text + "' is not a whole number";
        if (x < lo || x > hi)
          return std::to_string(x) + " is outside the allowed range " + range;
        return {};
      },
      "in " + range);
  }

  // Levenshtein distance, for "did you mean".
  inline std::size_t edit_distance(const std::string &a, const std::string &b)
  {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
      row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
      {
        std::size_t diagonal = row[0];
        row[0]               = i;
        for (std::size_t j = 1; j <= b.size(); ++j)
          {
            const std::size_t up = row[j];
            row[j]               = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal             = up;
          }
      }
    return row[b.size()];
  }

  // CLI11's message on one line; for an unknown first word, the closest
  // sub-command.
  inline std::string describe_parse_error(CLI::App &app, const CLI::ParseError &error, const int argc,
                                          char **argv)
  {
    std::string message = error.what();
    for (auto &c : message)
      if (c == '\n')
        c = ' ';
    // The first word on the command line should name a sub-command.
    if (argc > 1 && argv[1][0] != '-')
      {
        const std::string word = argv[1];
        bool known             = false;
        for (CLI::App *sub : app.get_subcommands([](CLI::App *) { return true; }))
          known = known || sub->get_name() == word;
        if (!known)
          {
            std::string best;
            std::size_t best_distance = 3; // at most two edits away
            for (CLI::App *sub : app.get_subcommands([](CLI::App *) { return true; }))
              {
                const std::size_t d = edit_distance(word, sub->get_name());
                if (d < best_distance)
                  {
                    best_distance = d;
                    best          = sub->get_name();
                  }
              }
            return "unknown command '" + word + "'" + (best.empty() ? "" : "; did you mean '" + best + "'?");
          }
      }
    return message;
  }
} // namespace beamslider

// Text from a file or the command line as it may appear in a one-line
// message: a binary mesh, a path with a newline or an escape sequence must
// not break the line, drive the terminal or flood it. Every byte outside
// printable ASCII is written as \n, \t, \r or \xNN, and the text is cut at
// `max_length` characters with "..." after it.
#pragma once

#include <cstddef>
#include <string>

namespace beamslider
{
  inline std::string printable(const std::string &text, const std::size_t max_length = 200)
  {
    static const char hex[] = "0123456789abcdef";
    std::string out;
    for (const char c : text)
      {
        if (out.size() >= max_length)
          return out + "...";
        const auto byte = static_cast<unsigned char>(c);
        if (byte == '\n')
          out += "\\n";
        else if (byte == '\t')
          out += "\\t";
        else if (byte == '\r')
          out += "\\r";
        else if (byte < 0x20 || byte >= 0x7f)
          out += std::string("\\x") + hex[byte >> 4] + hex[byte & 0xf];
        else
          out += c;
      }
    return out;
  }

  // A message as one line on a terminal: control bytes (a line break or an
  // escape sequence in a value the user gave) written as in printable(),
  // other text, UTF-8 included, as it is, and no length bound.
  inline std::string one_line(const std::string &text)
  {
    std::string out;
    for (const char c : text)
      {
        const auto byte = static_cast<unsigned char>(c);
        out += byte < 0x20 || byte == 0x7f ? printable(std::string(1, c)) : std::string(1, c);
      }
    return out;
  }
} // namespace beamslider

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
} // namespace beamslider

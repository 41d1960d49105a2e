// The switchable console stream, see console.h.
#include "io/console.h"

#include <iostream>
#include <streambuf>

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

    // A stream buffer that collects characters and hands each complete line
    // (without its '\n') to the sink.
    class LineSinkBuffer : public std::streambuf
    {
    public:
      std::function<void(const std::string &)> sink;

    protected:
      int_type overflow(const int_type c) override
      {
        if (traits_type::eq_int_type(c, traits_type::eof()))
          return traits_type::not_eof(c);
        if (c == '\n')
          {
            const std::string line = std::move(line_);
            line_.clear();
            if (sink)
              sink(line);
          }
        else
          line_ += traits_type::to_char_type(c);
        return c;
      }

    private:
      std::string line_;
    };

    LineSinkBuffer &sink_buffer()
    {
      static LineSinkBuffer buffer;
      return buffer;
    }

    std::ostream &sink_stream()
    {
      static std::ostream stream(&sink_buffer());
      return stream;
    }
  } // namespace

  std::ostream &console()
  {
    if (quiet_)
      return discarding_stream();
    return sink_buffer().sink ? sink_stream() : std::cout;
  }

  void set_quiet(const bool quiet) { quiet_ = quiet; }

  bool is_quiet() { return quiet_; }

  void set_console_sink(std::function<void(const std::string &)> sink)
  {
    sink_buffer().sink = std::move(sink);
    sink_stream().clear();
  }
} // namespace beamslider

// Checked result files, see output_file.h.
#include "contact/output_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <unistd.h>

namespace beamslider
{
  namespace
  {
    // The system's reason for the last failure, if it left one.
    std::string reason()
    {
      return errno ? std::string(std::strerror(errno)) : std::string("the stream reported an error");
    }
  } // namespace

  OutputFile::OutputFile(std::string path, const bool append)
    : path_(std::move(path))
  {
    errno = 0;
    out_.open(path_, append ? std::ios::out | std::ios::app : std::ios::out | std::ios::trunc);
    if (!out_.is_open())
      fail("cannot be opened for writing");
  }

  OutputFile::~OutputFile()
  {
    if (out_.is_open())
      out_.close();
  }

  void OutputFile::fail(const std::string &what)
  {
    const std::string message = "result file '" + path_ + "' " + what + ": " + reason();
    throw OutputError(message);
  }

  void OutputFile::check()
  {
    if (!out_)
      fail("could not be written");
  }

  void OutputFile::flush()
  {
    errno = 0;
    out_.flush();
    check();
  }

  void OutputFile::close()
  {
    flush();
    out_.close();
    if (out_.fail())
      fail("could not be closed");
  }

  void write_text_file(const std::string &path, const std::string &text)
  {
    OutputFile file(path);
    file.stream() << text;
    file.close();
  }

  void write_file_atomically(const std::string &path, const std::string &bytes)
  {
    const std::string tmp = path + ".tmp";
    errno                 = 0;
    const int fd          = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
      throw OutputError("file '" + tmp + "' cannot be opened for writing: " + reason());
    std::size_t done = 0;
    while (done < bytes.size())
      {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR)
          continue;
        if (n <= 0)
          {
            const std::string why = reason();
            ::close(fd);
            ::unlink(tmp.c_str());
            throw OutputError("file '" + tmp + "' could not be written: " + why);
          }
        done += static_cast<std::size_t>(n);
      }
    const bool synced     = ::fsync(fd) == 0;
    const std::string why = reason();
    const bool closed     = ::close(fd) == 0;
    if (!synced || !closed)
      {
        ::unlink(tmp.c_str());
        throw OutputError("file '" + tmp + "' could not be flushed to disk: " + why);
      }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      {
        const std::string why = reason();
        ::unlink(tmp.c_str());
        throw OutputError("file '" + tmp + "' could not be renamed to '" + path + "': " + why);
      }
  }

  std::string read_text_file(const std::string &path)
  {
    // POSIX calls rather than a stream: a stream reads a folder or a failing
    // disk as a short file and says nothing.
    errno        = 0;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
      throw FileReadError("file '" + path + "' cannot be opened for reading: " + reason());
    std::string text;
    char buffer[1 << 16];
    while (true)
      {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR)
          continue;
        if (n < 0)
          {
            const std::string why = reason(); // EISDIR for a folder
            ::close(fd);
            throw FileReadError("file '" + path + "' could not be read: " + why);
          }
        if (n == 0)
          break;
        text.append(buffer, static_cast<std::size_t>(n));
      }
    ::close(fd);
    return text;
  }

  std::string read_text_file_if_present(const std::string &path)
  {
    std::error_code error;
    const auto status = std::filesystem::symlink_status(path, error);
    if (status.type() == std::filesystem::file_type::not_found)
      return std::string();
    return read_text_file(path);
  }
} // namespace beamslider

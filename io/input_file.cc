// The guarded reader, see input_file.h.
#include "io/input_file.h"

#include <array>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace beamslider
{
  namespace
  {
    // What a file that is not a regular one is, for the message.
    std::string kind_of(const mode_t mode)
    {
      if (S_ISDIR(mode))
        return "a folder";
      if (S_ISFIFO(mode))
        return "a FIFO";
      if (S_ISCHR(mode) || S_ISBLK(mode))
        return "a device";
      if (S_ISSOCK(mode))
        return "a socket";
      return "not a regular file";
    }

    std::string refused(const std::string &path, const mode_t mode)
    {
      return "file '" + path + "' is not a regular file (" + kind_of(mode) + "); give a file";
    }

    std::string too_large(const std::string &path, const std::size_t size, const std::size_t max_bytes)
    {
      return "file '" + path + "' has " + (size ? std::to_string(size) : std::string("more than ") +
                                                                         std::to_string(max_bytes)) +
             " bytes; a file of its kind has at most " + std::to_string(max_bytes) + " bytes";
    }

    struct Descriptor
    {
      int fd;
      ~Descriptor()
      {
        if (fd >= 0)
          ::close(fd);
      }
    };
  } // namespace

  std::string read_text_file(const std::string &path, const std::size_t max_bytes)
  {
    struct stat info;
    if (::stat(path.c_str(), &info) != 0)
      throw FileReadError("file '" + path + "' cannot be opened for reading: " + std::strerror(errno));
    if (!S_ISREG(info.st_mode))
      throw FileReadError(refused(path, info.st_mode));
    if (static_cast<std::size_t>(info.st_size) > max_bytes)
      throw FileReadError(too_large(path, static_cast<std::size_t>(info.st_size), max_bytes));

    const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0)
      throw FileReadError("file '" + path + "' cannot be opened for reading: " + std::strerror(errno));
    if (::fstat(file.fd, &info) != 0 || !S_ISREG(info.st_mode))
      throw FileReadError(refused(path, info.st_mode));

    std::string text;
    text.reserve(static_cast<std::size_t>(info.st_size));
    std::array<char, 1 << 16> buffer;
    while (true)
      {
        const ssize_t n = ::read(file.fd, buffer.data(), buffer.size());
        if (n < 0 && errno == EINTR)
          continue;
        if (n < 0)
          throw FileReadError("file '" + path + "' could not be read: " + std::strerror(errno));
        if (n == 0)
          break;
        text.append(buffer.data(), static_cast<std::size_t>(n));
        // A file that grows while it is read stops at the limit too.
        if (text.size() > max_bytes)
          throw FileReadError(too_large(path, 0, max_bytes));
      }
    return text;
  }

  std::string read_text_file_if_present(const std::string &path, const std::size_t max_bytes)
  {
    struct stat info;
    if (::lstat(path.c_str(), &info) != 0 && errno == ENOENT)
      return std::string();
    return read_text_file(path, max_bytes);
  }
  std::string read_option_file(const std::string &path, const std::string &role, const std::size_t max_bytes)
  {
    try
      {
        return read_text_file(path, max_bytes);
      }
    catch (const FileReadError &e)
      {
        throw FileReadError(role + ": " + e.what());
      }
  }
} // namespace beamslider

// Checked result files, see output_file.h.
#include "io/output_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <map>
#include <sys/file.h>
#include <sys/stat.h>
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

  namespace
  {
    // A new file beside `path` for its next content: created here (never an
    // existing file or a link someone left there), renamed over `path` when
    // complete. Hidden, so that a folder listing shows only results.
    std::pair<int, std::string> create_temporary(const std::string &path)
    {
      static std::atomic<unsigned long> n_created{0}; // files may be opened from several threads
      const std::filesystem::path target(path);
      for (int attempt = 0;; ++attempt)
        {
          const std::string name = "." + target.filename().string() + "." + std::to_string(::getpid()) + "." +
                                   std::to_string(n_created++) + ".tmp";
          const std::string tmp = (target.parent_path() / name).string();
          errno                 = 0;
          const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
          if (fd >= 0 || errno != EEXIST || attempt > 100)
            return {fd, tmp};
        }
    }

    // Opens `fd`'s file in `out` (by /proc, so the name is not looked up
    // again, and a link put there meanwhile is not followed); closes fd.
    bool open_descriptor(std::ofstream &out, const int fd, const std::string &path, const std::ios::openmode mode)
    {
      const std::string by_descriptor = "/proc/self/fd/" + std::to_string(fd);
      out.open(std::filesystem::exists(by_descriptor) ? by_descriptor : path, mode);
      ::close(fd);
      return out.is_open();
    }
  } // namespace

  OutputFile::OutputFile(std::string path, const FileMode mode)
    : path_(std::move(path))
    , uncaught_(std::uncaught_exceptions())
  {
    errno = 0;
    if (mode == FileMode::whole)
      {
        // A folder in the result's place fails now, before any work, not
        // when the finished file is renamed.
        struct stat existing;
        if (::lstat(path_.c_str(), &existing) == 0 && S_ISDIR(existing.st_mode))
          {
            errno = EISDIR;
            fail("cannot be opened for writing");
          }
        const auto [fd, tmp] = create_temporary(path_);
        if (fd < 0)
          fail("cannot be opened for writing");
        temporary_ = tmp;
        if (!open_descriptor(out_, fd, temporary_, std::ios::out | std::ios::trunc))
          fail("cannot be opened for writing"); // removes the temporary
        return;
      }
    // A stream written in place: never through a link. A new one replaces
    // the link; a continued one (a resumed run) refuses it.
    struct stat link;
    if (mode == FileMode::stream && ::lstat(path_.c_str(), &link) == 0 && S_ISLNK(link.st_mode))
      ::unlink(path_.c_str());
    errno        = 0;
    const int fd = ::open(path_.c_str(),
                          O_WRONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC | (mode == FileMode::append ? O_APPEND : O_TRUNC),
                          0644);
    if (fd < 0)
      fail(errno == ELOOP ? "is a symbolic link, not written through" : "cannot be opened for writing");
    if (!open_descriptor(out_, fd, path_,
                         mode == FileMode::append ? std::ios::out | std::ios::app : std::ios::out | std::ios::trunc))
      fail("cannot be opened for writing");
  }

  void OutputFile::discard() noexcept
  {
    if (out_.is_open())
      out_.close();
    if (!temporary_.empty())
      ::unlink(temporary_.c_str());
    temporary_.clear();
  }

  OutputFile::~OutputFile()
  {
    if (!temporary_.empty() && std::uncaught_exceptions() <= uncaught_ && out_.is_open())
      {
        // Closed by scope, not by a failure: the result is complete.
        out_.close();
        if (!out_.fail() && std::rename(temporary_.c_str(), path_.c_str()) == 0)
          temporary_.clear();
      }
    discard();
  }

  void OutputFile::fail(const std::string &what)
  {
    const std::string message = "result file '" + path_ + "' " + what + ": " + reason();
    discard(); // a whole file never reaches its name half-written
    throw OutputError(message);
  }

  void OutputFile::check()
  {
    if (!out_)
      fail("could not be written");
  }

  void OutputFile::flush()
  {
    // A stream that failed already keeps the errno of its failed write (a
    // full disk, a file-size limit): it is the reason check() gives.
    if (out_)
      {
        errno = 0;
        out_.flush();
      }
    check();
  }

  void OutputFile::close()
  {
    if (!out_.is_open())
      return;
    flush();
    out_.close();
    if (out_.fail())
      fail("could not be closed");
    errno = 0;
    if (!temporary_.empty())
      {
        // rename() replaces a link or file at path_ itself, never its target.
        if (std::rename(temporary_.c_str(), path_.c_str()) != 0)
          fail("could not be renamed into place (from '" + temporary_ + "')");
        temporary_.clear();
      }
  }

  void write_text_file(const std::string &path, const std::string &text)
  {
    OutputFile file(path);
    file.stream() << text;
    file.close();
  }

  void write_file_atomically(const std::string &path, const std::string &bytes)
  {
    const auto [fd, tmp] = create_temporary(path);
    if (fd < 0)
      throw OutputError("result file '" + path + "' cannot be opened for writing (as '" + tmp + "'): " + reason());
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
            throw OutputError("result file '" + path + "' could not be written: " + why);
          }
        done += static_cast<std::size_t>(n);
      }
    const bool synced     = ::fsync(fd) == 0;
    const std::string why = reason();
    const bool closed     = ::close(fd) == 0;
    if (!synced || !closed)
      {
        ::unlink(tmp.c_str());
        throw OutputError("result file '" + path + "' could not be flushed to disk: " + why);
      }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      {
        const std::string why = reason();
        ::unlink(tmp.c_str());
        throw OutputError("result file '" + path + "' could not be renamed into place (from '" + tmp + "'): " + why);
      }
  }

  namespace
  {
    // The folders this process holds: the folder as given, made absolute and
    // normal, and its lock file's descriptor (open while held).
    std::map<std::string, int> &held_folders()
    {
      static std::map<std::string, int> held;
      return held;
    }
  } // namespace

  void lock_output_folder(const std::string &dir)
  {
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(dir, ec);
    const std::string id                  = ec ? dir : canonical.string();
    if (held_folders().count(id))
      return;
    const std::string path = (std::filesystem::path(dir) / output_folder_lock_name()).string();
    errno                  = 0;
    // O_CLOEXEC: a chart's Python started by the run must not keep the lock.
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
      throw OutputError("output folder '" + dir + "' cannot be locked for this run ('" + path + "'): " + reason());
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
      {
        const int why = errno;
        char owner[32] = {};
        const ssize_t n = why == EWOULDBLOCK ? ::pread(fd, owner, sizeof owner - 1, 0) : 0;
        std::string pid(owner, n > 0 ? static_cast<std::size_t>(n) : 0);
        while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' '))
          pid.pop_back();
        ::close(fd);
        if (why == EWOULDBLOCK)
          throw FolderInUseError("output folder '" + dir + "' is in use by process " +
                                 (pid.empty() ? std::string("(not known yet)") : pid) +
                                 "; one folder holds one run: wait for it, stop it or choose another --output");
        errno = why;
        throw OutputError("output folder '" + dir + "' cannot be locked for this run: " + reason());
      }
    // Ours now: the process id, for the message another run gives.
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size()))
      {
        const std::string why = reason();
        ::close(fd);
        throw OutputError("output folder '" + dir + "': the lock file '" + path + "' cannot be written: " + why);
      }
    held_folders()[id] = fd;
  }

  std::vector<std::string> held_output_folders()
  {
    std::vector<std::string> folders;
    for (const auto &held : held_folders())
      folders.push_back(held.first);
    return folders;
  }

  void release_output_folders()
  {
    for (const auto &[dir, fd] : held_folders())
      ::close(fd); // closing the last descriptor drops the flock
    held_folders().clear();
  }
} // namespace beamslider

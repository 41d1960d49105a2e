// Result files that cannot fail silently.
//
// A run whose results did not reach the disk must not report success: a
// read-only folder, a folder where a file should be, a full disk or a
// file-size limit all surface as an OutputError that names the file and the
// reason, and the program exits with status 1. OutputFile checks the open,
// every flush and the close; write_text_file does the same for a whole text.
//
// The process ignores SIGXFSZ (see interruption.h), so that a file-size limit
// makes the write fail with EFBIG instead of killing the process.
//
// Reading back what a run wrote (a resumed map's settings, a checkpoint, a
// part of the report written by a second process) is checked the same way:
// read_text_file throws a FileReadError that names the file and the system's
// reason, rather than returning the part it got as if it were the whole.
#pragma once

#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>

namespace beamslider
{
  // Results could not be written. Exit status 1.
  class OutputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // A file could not be read (not there, a folder, no permission, an I/O
  // error). Callers rethrow it as their own kind where the file was the
  // user's input (a scene file, a checkpoint to resume).
  class FileReadError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  class OutputFile
  {
  public:
    // Opens (truncates) `path` for writing; `append` keeps what is there.
    // Throws OutputError if it cannot be opened.
    explicit OutputFile(std::string path, bool append = false);
    OutputFile(const OutputFile &) = delete;
    OutputFile &operator=(const OutputFile &) = delete;
    // Closes without throwing; call close() to learn whether the tail was written.
    ~OutputFile();

    std::ostream &stream() { return out_; }
    const std::string &path() const { return path_; }

    // Pushes buffered text to the file; throws OutputError on failure.
    void flush();
    // Flushes and closes; throws OutputError on failure.
    void close();
    // Throws OutputError if a write has failed since the last check.
    void check();

  private:
    [[noreturn]] void fail(const std::string &what);
    std::string path_;
    std::ofstream out_;
  };

  // Writes `text` to `path` (replacing it), checked; throws OutputError.
  void write_text_file(const std::string &path, const std::string &text);

  // Writes `bytes` to `path` atomically: into `path.tmp`, flushed to disk,
  // then renamed over `path`, so that a reader sees either the old or the new
  // file whole, never a half-written one. Throws OutputError.
  void write_file_atomically(const std::string &path, const std::string &bytes);

  // The whole of `path`, byte for byte. Throws FileReadError if it cannot be
  // opened or a read fails.
  std::string read_text_file(const std::string &path);

  // The same, or "" if nothing is at `path` (a folder a run is about to
  // start in); a file that is there but cannot be read still throws.
  std::string read_text_file_if_present(const std::string &path);
} // namespace beamslider

// Result files that cannot fail silently.
//
// A run whose results did not reach the disk must not report success: a
// read-only folder, a folder where a file should be, a full disk or a
// file-size limit all surface as an OutputError that names the file and the
// reason, and the program exits with status 1. OutputFile checks the open,
// every flush and the close; write_text_file does the same for a whole text.
//
// A result file is written whole: into a temporary file in its folder,
// renamed over the result when closed, so that a reader (or a run killed
// half-way) never leaves half a file under the result's name, and a symbolic
// link in the result's place is replaced, never written through. A stream
// that grows during a run and must survive a kill -9 (trace.csv) is written
// in place instead, but never through a link either (FileMode::stream).
//
// The process ignores SIGXFSZ (see interruption.h), so that a file-size limit
// makes the write fail with EFBIG instead of killing the process.
//
// Reading back what a run wrote goes through io/input_file.h.
#pragma once

#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  // Results could not be written. Exit status 1.
  class OutputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // Another live process holds the output folder (lock_output_folder).
  // Exit status 1, and its message is the whole story.
  class FolderInUseError : public OutputError
  {
  public:
    using OutputError::OutputError;
  };

  enum class FileMode
  {
    whole,  // a temporary file, renamed over `path` by close()
    stream, // `path` itself, truncated (a link in its place removed first)
    append  // `path` itself, kept and continued (a link is refused)
  };

  class OutputFile
  {
  public:
    // Opens `path` for writing as `mode` says; throws OutputError if it
    // cannot be opened.
    explicit OutputFile(std::string path, FileMode mode = FileMode::whole);
    // `append`: FileMode::append, else FileMode::whole.
    OutputFile(std::string path, bool append)
      : OutputFile(std::move(path), append ? FileMode::append : FileMode::whole)
    {}
    OutputFile(const OutputFile &) = delete;
    OutputFile &operator=(const OutputFile &) = delete;
    // Closes without throwing; call close() to learn whether the tail was
    // written. A whole file is renamed into place unless an exception is on
    // its way (a run that failed half-way): then the temporary is removed.
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
    void discard() noexcept;
    std::string path_, temporary_; // temporary_: "" unless FileMode::whole
    std::ofstream out_;
    int uncaught_ = 0; // std::uncaught_exceptions() when opened
  };

  // Writes `text` to `path` (replacing it, whole), checked; throws OutputError.
  void write_text_file(const std::string &path, const std::string &text);

  // Writes `bytes` to `path` atomically: into a new temporary file beside
  // it, flushed to disk, then renamed over `path`, so that a reader sees
  // either the old or the new file whole, never a half-written one (and a
  // power cut neither). Throws OutputError.
  void write_file_atomically(const std::string &path, const std::string &bytes);

  // A folder one run writes into, for as long as the process lives (or
  // until release_output_folders): an flock()ed file `.beamslider.lock` in
  // it holds the owner's process id. The kernel drops the lock when the
  // process ends, however it ends, so a kill -9 leaves no stale lock. A
  // folder this process holds already is not locked twice. Throws
  // OutputError ("output folder 'X' is in use by process P") if another
  // process holds it; nothing else in the folder is touched then.
  void lock_output_folder(const std::string &dir);
  // The folders this process holds (absolute, normal paths).
  std::vector<std::string> held_output_folders();
  // Lets go of every folder this process holds (a command run in a process
  // that lives on: the Python module).
  void release_output_folders();
  // The lock file's name, for tests that hold a folder themselves.
  inline const char *output_folder_lock_name() { return ".beamslider.lock"; }

} // namespace beamslider

// io/output_file.h, and its reading half io/input_file.h: read_text_file gives back every
// byte a write put there (a file larger than one read, with NUL bytes and no
// final line break), and refuses what is not a readable file with an error
// that names it; read_text_file_if_present reads a missing file as empty but
// still refuses a folder.
#include "io/input_file.h"
#include "io/output_file.h"

#include "tests/fresh_folder.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <sys/file.h>
#include <unistd.h>

using namespace beamslider;
using beamslider::testing::fresh_folder;

namespace
{
  // Raises `f` and checks that the error names `path`.
  template <typename F>
  void expect_read_error_naming(F f, const std::string &path)
  {
    try
      {
        f();
        ADD_FAILURE() << "no FileReadError for '" << path << "'";
      }
    catch (const FileReadError &e)
      {
        EXPECT_NE(std::string(e.what()).find("'" + path + "'"), std::string::npos) << e.what();
      }
  }
} // namespace

TEST(ReadTextFile, GivesBackEveryByteOfAFileLargerThanOneRead)
{
  const auto folder = fresh_folder("read_text_file_bytes");
  // 200 000 bytes (three reads of 64 KiB and a rest), every byte value, NUL
  // included, no line break at the end.
  std::string bytes(200000, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<char>((i * 7919) % 256);
  const std::string path = (folder / "data.bin").string();
  write_text_file(path, bytes);
  EXPECT_EQ(read_text_file(path), bytes);
  EXPECT_EQ(read_text_file_if_present(path), bytes);

  write_text_file(path, "");
  EXPECT_EQ(read_text_file(path), "");
  std::filesystem::remove_all(folder);
}

TEST(ReadTextFile, RefusesAMissingFileAndAFolderNamingThem)
{
  const auto folder          = fresh_folder("read_text_file_refusals");
  const std::string missing = (folder / "missing.txt").string();
  expect_read_error_naming([&] { read_text_file(missing); }, missing);
  EXPECT_EQ(read_text_file_if_present(missing), "");

  // A folder opens for reading on Linux; a stream would read it as an empty
  // file. Present or not, it is not a file.
  const std::string sub = (folder / "a-folder").string();
  std::filesystem::create_directories(sub);
  expect_read_error_naming([&] { read_text_file(sub); }, sub);
  expect_read_error_naming([&] { read_text_file_if_present(sub); }, sub);
  std::filesystem::remove_all(folder);
}

// The writing half: a whole file appears under its name only when closed
// (a temporary beside it until then, removed if a failure unwinds it), and a
// symbolic link at the result's name is replaced, never written through; a
// stream replaces a link too, and continuing one through a link is refused.
TEST(OutputFile, WholeFilesAndStreamsReplaceALinkAndNeverWriteThroughIt)
{
  namespace fs          = std::filesystem;
  const auto folder     = fresh_folder("output_file_links");
  const fs::path target = folder / "target.txt";
  write_text_file(target.string(), "kept\n");
  for (const FileMode mode : {FileMode::whole, FileMode::stream})
    {
      const fs::path link = folder / "result.csv";
      fs::remove(link);
      fs::create_symlink(target, link);
      OutputFile file(link.string(), mode);
      file.stream() << "result\n";
      file.close();
      EXPECT_FALSE(fs::is_symlink(link));
      EXPECT_EQ(read_text_file(link.string()), "result\n");
      EXPECT_EQ(read_text_file(target.string()), "kept\n");
    }
  const fs::path link = folder / "continued.csv";
  fs::create_symlink(target, link);
  EXPECT_THROW(OutputFile(link.string(), FileMode::append), OutputError);
  EXPECT_EQ(read_text_file(target.string()), "kept\n");

  // Half a file is never under the result's name: while open, and after a
  // failure unwound it, only the old content is there and no temporary.
  const std::string path = (folder / "summary.md").string();
  write_text_file(path, "old\n");
  try
    {
      OutputFile file(path);
      file.stream() << "half of a new";
      file.flush();
      EXPECT_EQ(read_text_file(path), "old\n");
      throw std::runtime_error("the run failed");
    }
  catch (const std::runtime_error &)
    {}
  EXPECT_EQ(read_text_file(path), "old\n");
  for (const auto &entry : fs::directory_iterator(folder))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
  fs::remove_all(folder);
}

// A folder held through another open file description (as another process
// would) is refused with the holder's process id; the lock file is the only
// file touched, and once the holder lets go the folder can be taken.
TEST(OutputFolder, AHeldFolderIsRefusedNamingItsHolder)
{
  const auto folder      = fresh_folder("output_folder_lock");
  const std::string lock = (folder / output_folder_lock_name()).string();
  const int fd           = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const std::string holder = "4242\n";
  ASSERT_EQ(::write(fd, holder.data(), holder.size()), static_cast<ssize_t>(holder.size()));
  try
    {
      lock_output_folder(folder.string());
      ADD_FAILURE() << "a held folder was taken";
    }
  catch (const FolderInUseError &e)
    {
      EXPECT_EQ(std::string(e.what()).rfind("output folder '" + folder.string() + "' is in use by process 4242;", 0),
                0u)
        << e.what();
    }
  ::close(fd); // the holder ends
  EXPECT_NO_THROW(lock_output_folder(folder.string()));
  EXPECT_NO_THROW(lock_output_folder(folder.string())); // held by this process already: not twice
  EXPECT_EQ(read_text_file(lock), std::to_string(::getpid()) + "\n");
  release_output_folders();
  std::filesystem::remove_all(folder);
}

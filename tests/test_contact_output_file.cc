// contact/output_file.h, the reading half: read_text_file gives back every
// byte a write put there (a file larger than one read, with NUL bytes and no
// final line break), and refuses what is not a readable file with an error
// that names it; read_text_file_if_present reads a missing file as empty but
// still refuses a folder.
#include "contact/output_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

using namespace beamslider;

namespace
{
  // A fresh folder under the system's temporary folder, removed at the end.
  struct ScratchFolder
  {
    ScratchFolder()
      : path(std::filesystem::temp_directory_path() /
             ("beamslider-output-file-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
              ::testing::UnitTest::GetInstance()->current_test_info()->name()))
    {
      std::filesystem::remove_all(path);
      std::filesystem::create_directories(path);
    }
    ~ScratchFolder() { std::filesystem::remove_all(path); }
    std::string file(const std::string &name) const { return (path / name).string(); }
    std::filesystem::path path;
  };

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
  const ScratchFolder folder;
  // 200 000 bytes (three reads of 64 KiB and a rest), every byte value, NUL
  // included, no line break at the end.
  std::string bytes(200000, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<char>((i * 7919) % 256);
  const std::string path = folder.file("data.bin");
  write_text_file(path, bytes);
  EXPECT_EQ(read_text_file(path), bytes);
  EXPECT_EQ(read_text_file_if_present(path), bytes);

  write_text_file(path, "");
  EXPECT_EQ(read_text_file(path), "");
}

TEST(ReadTextFile, RefusesAMissingFileAndAFolderNamingThem)
{
  const ScratchFolder folder;
  const std::string missing = folder.file("missing.txt");
  expect_read_error_naming([&] { read_text_file(missing); }, missing);
  EXPECT_EQ(read_text_file_if_present(missing), "");

  // A folder opens for reading on Linux; a stream would read it as an empty
  // file. Present or not, it is not a file.
  const std::string sub = folder.file("a-folder");
  std::filesystem::create_directories(sub);
  expect_read_error_naming([&] { read_text_file(sub); }, sub);
  expect_read_error_naming([&] { read_text_file_if_present(sub); }, sub);
}

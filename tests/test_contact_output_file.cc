// contact/output_file.h, the reading half: read_text_file gives back every
// byte a write put there (a file larger than one read, with NUL bytes and no
// final line break), and refuses what is not a readable file with an error
// that names it; read_text_file_if_present reads a missing file as empty but
// still refuses a folder.
#include "contact/output_file.h"

#include "tests/fresh_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

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

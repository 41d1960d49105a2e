// io/csv_writer.h: rows read back as they were written, by the
// writer's own cells() and by the RFC 4180 rules Python's csv module follows
// (a cell with a comma, quote or line break in double quotes, quotes doubled);
// append mode writes no second header; a row of the wrong width is refused.
#include "io/csv_writer.h"
#include "tests/read_text_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

using namespace beamslider;
using beamslider::testing::read_file;

TEST(CsvWriter, CellsWithCommasAndQuotesReadBackAsOneCell)
{
  const std::vector<std::string> row = {"fig10", "Excitation/Frequency=145, Excitation/Acceleration amplitude=20",
                                        "says \"stop\" here", "", "plain", ","};
  const std::string line = CsvWriter::line(row);
  // Written by hand from RFC 4180: quoted cells, inner quotes doubled.
  EXPECT_EQ(line, "fig10,\"Excitation/Frequency=145, Excitation/Acceleration amplitude=20\","
                  "\"says \"\"stop\"\" here\",,plain,\",\"");
  EXPECT_EQ(CsvWriter::cells(line), row);
  // Cells that need nothing stay as they are (map rows travel this way).
  EXPECT_EQ(CsvWriter::line({"124", "14", "0.3", "completed"}), "124,14,0.3,completed");
  EXPECT_EQ(CsvWriter::cells("a,,b,"), (std::vector<std::string>{"a", "", "b", ""}));
}

TEST(CsvWriter, AppendingWritesNoSecondHeaderAndWrongWidthsAreRefused)
{
  const std::string path = ::testing::TempDir() + "csv_writer_test.csv";
  {
    CsvWriter csv(path, {"t_s", "note"});
    csv.numbers({0.5, 2.}, 6);
    EXPECT_THROW(csv.row({"only one"}), std::logic_error);
  }
  {
    CsvOptions append;
    append.append = true;
    CsvWriter csv(path, {"t_s", "note"}, append);
    csv.row({CsvWriter::cell(1.25), "a, b"});
    csv.close();
  }
  EXPECT_EQ(read_file(path), "t_s,note\n0.5,2\n1.25,\"a, b\"\n");
  std::remove(path.c_str());
}

// The coefficient files (verification/cli/coefficient_files.h): one-based
// mode numbers, every double to the last bit, a failed write reported.
#include "io/output_file.h"
#include "verification/cli/coefficient_files.h"
#include "tests/read_text_file.h"

#include <gtest/gtest.h>

using namespace beamslider;
using beamslider::testing::read_file;

TEST(CoefficientFiles, CsvHasOneBasedModeNumbersAndFullPrecision)
{
  const std::vector<CubicTerm> terms = {{0, 0, 0, 0, 1.2345678901234567e12}, {2, 0, 1, 2, -3.5}};
  const std::string dir = ::testing::TempDir();
  write_coefficients_csv(dir + "coefficients.csv", terms);
  EXPECT_EQ(read_file(dir + "coefficients.csv"), "n,j,k,l,value\n1,1,1,1,1234567890123.4568\n3,1,2,3,-3.5\n");
  write_quadratic_coefficients_csv(dir + "quadratic.csv", {{1, 0, 1, 0.25}});
  EXPECT_EQ(read_file(dir + "quadratic.csv"), "n,j,k,value\n2,1,2,0.25\n");
  EXPECT_THROW(write_coefficients_csv("/nonexistent-dir/coefficients.csv", terms), OutputError);
}

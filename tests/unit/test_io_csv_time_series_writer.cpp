// The time-series CSV: header "name [unit]", rows that read back to the same doubles,
// rows on disk as soon as they are written (a run can be followed, a crash keeps them).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <gtest/gtest.h>

#include "io/csv_time_series_writer.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

class CsvTimeSeriesWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "regodem-csv-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    directory_ = pattern;
  }
  void TearDown() override { fs::remove_all(directory_); }

  static std::vector<std::string> read_lines(const fs::path& path) {
    std::ifstream input(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(input, line);) lines.push_back(line);
    return lines;
  }
  static std::vector<std::string> split_fields(const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream stream(line);
    for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
    return fields;
  }

  fs::path directory_;
  const std::vector<SeriesColumn> columns_{
      {"time", "s"}, {"kinetic energy", "J"}, {"particles", "-"}};
};

TEST_F(CsvTimeSeriesWriterTest, HeaderNamesEachColumnWithItsUnit) {
  { CsvTimeSeriesWriter writer(directory_ / "series.csv", columns_); }
  const std::vector<std::string> lines = read_lines(directory_ / "series.csv");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "time [s],kinetic energy [J],particles [-]");
}

TEST_F(CsvTimeSeriesWriterTest, RowsReadBackToTheSameDoubles) {
  const std::vector<std::vector<double>> rows{
      {0.0, 0.1, 1.0},
      {1.0 / 3.0, 6.02214076e23, -2.5e17},
      {std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(), 1e-300},
      {std::nextafter(1.0, 2.0), -0.0, 123456789.0},
  };
  {
    CsvTimeSeriesWriter writer(directory_ / "series.csv", columns_);
    for (const auto& row : rows) writer.write_row(row);
    EXPECT_EQ(writer.rows_written(), rows.size());
  }
  const std::vector<std::string> lines = read_lines(directory_ / "series.csv");
  ASSERT_EQ(lines.size(), rows.size() + 1);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::vector<std::string> fields = split_fields(lines[r + 1]);
    ASSERT_EQ(fields.size(), columns_.size()) << lines[r + 1];
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const double read_back = std::strtod(fields[c].c_str(), nullptr);
      EXPECT_EQ(read_back, rows[r][c]) << "row " << r << " column " << c << ": " << fields[c];
      EXPECT_EQ(std::signbit(read_back), std::signbit(rows[r][c]));
    }
  }
}

TEST_F(CsvTimeSeriesWriterTest, RowsAreOnDiskBeforeTheWriterCloses) {
  CsvTimeSeriesWriter writer(directory_ / "series.csv", columns_);
  writer.write_row(std::vector<double>{0.5, 2.0, 10.0});
  const std::vector<std::string> lines = read_lines(directory_ / "series.csv");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1], "0.5,2,10");
}

TEST_F(CsvTimeSeriesWriterTest, RowOfWrongLengthIsRefusedAndNotWritten) {
  CsvTimeSeriesWriter writer(directory_ / "series.csv", columns_);
  EXPECT_THROW(writer.write_row(std::vector<double>{1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(writer.write_row(std::vector<double>{1.0, 2.0, 3.0, 4.0}), std::invalid_argument);
  EXPECT_EQ(writer.rows_written(), 0u);
  EXPECT_EQ(read_lines(directory_ / "series.csv").size(), 1u);
}

TEST_F(CsvTimeSeriesWriterTest, HeaderFieldWithCommaOrQuoteIsQuoted) {
  EXPECT_EQ(csv_header_field({"force, normal", "N"}), "\"force, normal [N]\"");
  EXPECT_EQ(csv_header_field({"say \"hi\"", "-"}), "\"say \"\"hi\"\" [-]\"");
  EXPECT_EQ(csv_header_field({"temperature", "K"}), "temperature [K]");
}

TEST_F(CsvTimeSeriesWriterTest, ReplacesAnOldFile) {
  { std::ofstream(directory_ / "series.csv") << "stale,content\n1,2\n3,4\n"; }
  { CsvTimeSeriesWriter writer(directory_ / "series.csv", columns_); }
  EXPECT_EQ(read_lines(directory_ / "series.csv").size(), 1u);
}

// A run resumed by a version that writes other columns (real_time was added) must not
// append its rows under the old header: refused, the file as it was.
TEST_F(CsvTimeSeriesWriterTest, ContinuingAFileOfOtherColumnsIsRefusedAndChangesNothing) {
  const std::string old = "time [s],x [m]\n1,2\n3,4\n";
  { std::ofstream(directory_ / "series.csv") << old; }
  try {
    CsvTimeSeriesWriter writer(directory_ / "series.csv", columns_.size(), 16, 1);
    FAIL() << "expected std::system_error";
  } catch (const std::system_error& error) {
    EXPECT_NE(std::string(error.what()).find("its header has 2 columns, this version writes " +
                                             std::to_string(columns_.size())),
              std::string::npos)
        << error.what();
  }
  std::ifstream in(directory_ / "series.csv", std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()), old);
}

TEST_F(CsvTimeSeriesWriterTest, UnwritablePathThrowsNamingIt) {
  try {
    CsvTimeSeriesWriter writer(directory_ / "missing" / "series.csv", columns_);
    FAIL() << "expected std::system_error";
  } catch (const std::system_error& error) {
    EXPECT_NE(std::string(error.what()).find("missing/series.csv"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace regodem

// `regodem plot`, run as a user runs it on a small run's outputs: PNG files of the
// documented size (read from the PNG header), overlays with labels, the section image and
// its layout (from the decoded pixels), and clear refusals of bad arguments and broken CSV
// files.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>  // regodem_lib links zlib (compressed snapshots); the tests decode PNG files with it

#include "regodem_process.hpp"

namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kFigureWidth = 960, kFigureHeight = 600;  // docs/outputs.md

struct Result {
  int exit_code = -1;
  std::string output;
};

Result run(const std::string& arguments) {
  const std::string command = std::string("'") + REGODEM_BINARY + "' " + arguments + " </dev/null 2>&1";
  Result result;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) result.output.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

struct PngSize {
  bool valid = false;
  std::uint32_t width = 0, height = 0;
  std::uintmax_t bytes = 0;
};

/// The signature, then the IHDR chunk: width and height as big-endian 32-bit numbers.
PngSize png_size(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  PngSize size;
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || bytes.compare(12, 4, "IHDR") != 0)
    return size;
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  size.valid = true;
  size.width = be32(16);
  size.height = be32(20);
  size.bytes = bytes.size();
  return size;
}

/// A PNG as matplotlib writes it (8-bit RGB or RGBA, not interlaced), decoded to
/// whether each pixel is background (near white).
struct Image {
  std::uint32_t width = 0, height = 0;
  std::vector<bool> ink;  // row by row: true where the pixel is not background
  bool at(std::uint32_t x, std::uint32_t y) const { return ink[std::size_t{y} * width + x]; }
};

bool decode_png(const fs::path& path, Image& image, std::string& why) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.size() < 33 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return why = "not a PNG", false;
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  std::string compressed;
  int channels = 0;
  for (std::size_t at = 8; at + 8 <= bytes.size();) {
    const std::uint32_t length = be32(at);
    const std::string type = bytes.substr(at + 4, 4);
    if (at + 12 + length > bytes.size()) return why = "truncated chunk", false;
    if (type == "IHDR") {
      image.width = be32(at + 8);
      image.height = be32(at + 12);
      const int depth = static_cast<unsigned char>(bytes[at + 16]), colour = static_cast<unsigned char>(bytes[at + 17]);
      const int interlace = static_cast<unsigned char>(bytes[at + 20]);
      if (depth != 8 || (colour != 2 && colour != 6) || interlace != 0)
        return why = "not 8-bit RGB(A) without interlacing", false;
      channels = colour == 6 ? 4 : 3;
    } else if (type == "IDAT") {
      compressed += bytes.substr(at + 8, length);
    }
    at += 12 + length;
  }
  if (channels == 0) return why = "no IHDR", false;
  const std::size_t stride = std::size_t{image.width} * static_cast<std::size_t>(channels);
  std::vector<unsigned char> raw((stride + 1) * image.height);
  uLongf raw_size = static_cast<uLongf>(raw.size());
  if (::uncompress(raw.data(), &raw_size, reinterpret_cast<const Bytef*>(compressed.data()),
                   static_cast<uLong>(compressed.size())) != Z_OK ||
      raw_size != raw.size())
    return why = "bad image data", false;
  // Undo each row's filter (PNG specification, section 9).
  std::vector<unsigned char> pixels(stride * image.height), zero(stride, 0);
  const auto bpp = static_cast<std::size_t>(channels);
  for (std::uint32_t y = 0; y < image.height; ++y) {
    const unsigned char filter = raw[y * (stride + 1)];
    const unsigned char* in_row = &raw[y * (stride + 1) + 1];
    unsigned char* row = &pixels[y * stride];
    const unsigned char* up = y == 0 ? zero.data() : &pixels[(y - 1) * stride];
    for (std::size_t i = 0; i < stride; ++i) {
      const int a = i >= bpp ? row[i - bpp] : 0, b = up[i], c = i >= bpp ? up[i - bpp] : 0;
      int predictor = 0;
      switch (filter) {
        case 0: predictor = 0; break;
        case 1: predictor = a; break;
        case 2: predictor = b; break;
        case 3: predictor = (a + b) / 2; break;
        case 4: {
          const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
          predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
          break;
        }
        default: return why = "bad row filter", false;
      }
      row[i] = static_cast<unsigned char>(in_row[i] + predictor);
    }
  }
  image.ink.assign(std::size_t{image.width} * image.height, false);
  for (std::size_t p = 0; p < image.ink.size(); ++p) {
    const unsigned char* px = &pixels[p * bpp];
    image.ink[p] = px[0] < 245 || px[1] < 245 || px[2] < 245;  // not white (anti-aliasing included)
  }
  return true;
}

class PlotCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("regodem_plot_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    for (const char* name : {"sieve", "no_sieve"}) {
      const Result r = run(std::string("run '" REGODEM_SOURCE_DIR "/tests/data/scenarios/snapshots_small.yaml' "
                                       "--threads 1 -o '") +
                           (root_ / name).string() + "'");
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  void SetUp() override {
    const Result probe = run("plot '" + (root_ / "sieve").string() + "' --out '" + (root_ / "probe").string() + "'");
    if (probe.exit_code != 0 && probe.output.find("matplotlib") != std::string::npos)
      GTEST_SKIP() << "matplotlib is not installed for /usr/bin/python3: " << probe.output;
  }

  static fs::path root_;
};

fs::path PlotCommand::root_;

TEST_F(PlotCommand, WritesEveryFigureOfTheDocumentedSize) {
  const fs::path out = root_ / "one";
  const Result r = run("plot '" + (root_ / "sieve").string() + "' --section --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"temperature.png", "wall_temperatures.png", "energy_balance.png", "wall_forces.png",
                           "mechanics.png", "section.png"}) {
    const PngSize size = png_size(out / name);
    EXPECT_TRUE(size.valid) << name << " is missing or not a PNG\n" << r.output;
    EXPECT_EQ(size.width, kFigureWidth) << name;
    EXPECT_EQ(size.height, kFigureHeight) << name;
    EXPECT_GT(size.bytes, 5000u) << name << " is suspiciously small for a figure with data";
  }
}

TEST_F(PlotCommand, TheSectionFillsItsFigureAndNothingRunsOffTheEdges) {
  // Issue 22: the section left half of the image blank and its title ran off the right
  // edge. Tolerances, set before measuring: the outermost 2 pixel columns on each side
  // and the top 2 rows are background (nothing cut at an edge); the columns that hold
  // only background make up at most 15 % of the width, and no run of them is wider than
  // 8 % (77 px).
  // A long label makes a long title.
  const fs::path out = root_ / "layout";
  const Result r = run("plot '" + (root_ / "sieve").string() +
                       "' --labels 'small heated cup with a two-segment thermal sieve' --section --out '" +
                       out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Image image;
  std::string why;
  ASSERT_TRUE(decode_png(out / "section.png", image, why)) << why;
  ASSERT_EQ(image.width, kFigureWidth);
  ASSERT_EQ(image.height, kFigureHeight);
  auto column_blank = [&](std::uint32_t x) {
    for (std::uint32_t y = 0; y < image.height; ++y)
      if (image.at(x, y)) return false;
    return true;
  };
  auto row_blank = [&](std::uint32_t y) {
    for (std::uint32_t x = 0; x < image.width; ++x)
      if (image.at(x, y)) return false;
    return true;
  };
  for (const std::uint32_t x : {0u, 1u, image.width - 2, image.width - 1})
    EXPECT_TRUE(column_blank(x)) << "something runs off the image at column " << x;
  for (const std::uint32_t y : {0u, 1u}) EXPECT_TRUE(row_blank(y)) << "something runs off the top at row " << y;
  std::uint32_t blank = 0, run_length = 0, longest = 0;
  for (std::uint32_t x = 0; x < image.width; ++x) {
    if (column_blank(x)) {
      ++blank;
      longest = std::max(longest, ++run_length);
    } else {
      run_length = 0;
    }
  }
  EXPECT_LE(blank, image.width * 15 / 100) << blank << " of " << image.width << " columns are blank";
  EXPECT_LE(longest, image.width * 8 / 100) << "a blank band " << longest << " px wide";
}

TEST_F(PlotCommand, OverlaysRunsWithLabelsAndDefaultsToThePlotsFolder) {
  const Result r = run("plot '" + (root_ / "sieve").string() + "' '" + (root_ / "no_sieve").string() +
                       "' --labels 'with sieve,without' --section");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path out = root_ / "sieve" / "plots";
  EXPECT_TRUE(png_size(out / "temperature.png").valid) << r.output;
  EXPECT_TRUE(png_size(out / "section_with_sieve.png").valid) << r.output;
  EXPECT_TRUE(png_size(out / "section_without.png").valid) << r.output;
}

TEST_F(PlotCommand, PlotsFurtherCsvFilesAsProfiles) {
  // Profiles come in a later version; any CSV with "name [unit]" headers is drawn.
  const fs::path run_dir = root_ / "sieve";
  {
    std::ofstream csv(run_dir / "radial_profile.csv");
    csv << "distance [m],temperature [K]\n0,250\n0.001,260\n0.002,280\n";
  }
  const fs::path out = root_ / "profiles";
  const Result r = run("plot '" + run_dir.string() + "' --out '" + out.string() + "'");
  fs::remove(run_dir / "radial_profile.csv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const PngSize size = png_size(out / "radial_profile.png");
  EXPECT_TRUE(size.valid) << r.output;
  EXPECT_EQ(size.width, kFigureWidth);
}

TEST_F(PlotCommand, DrawsAProfileAsOneLinePerInstant) {
  // profiles/NAME.csv as `measurements.profiles` writes it: long form, two instants.
  const fs::path run_dir = root_ / "sieve";
  fs::create_directories(run_dir / "profiles");
  {
    std::ofstream csv(run_dir / "profiles" / "radial.csv");
    csv << "time [s],depth [m],radius [m],temperature_mean [K],temperature_min [K],temperature_max [K],count [-]\n"
           "1,0.075,0.0005,250,240,260,3\n1,0.075,0.0015,230,220,240,4\n"
           "2,0.1,0.0005,270,260,280,3\n2,0.1,0.0015,nan,nan,nan,0\n";
  }
  const fs::path out = root_ / "profile_plots";
  const Result r = run("plot '" + run_dir.string() + "' --out '" + out.string() + "'");
  fs::remove_all(run_dir / "profiles");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(png_size(out / "profiles_radial.png").valid) << r.output;
}

TEST_F(PlotCommand, RefusesBadArgumentsWithExitStatusTwo) {
  const std::string sieve = "'" + (root_ / "sieve").string() + "'";
  Result r = run("plot '" + (root_ / "missing").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("is not a directory"), std::string::npos) << r.output;
  r = run("plot " + sieve + " " + sieve + " --labels only_one");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("1 label for 2 runs"), std::string::npos) << r.output;
  r = run("plot " + sieve + " --section --section-through 1,2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("three numbers"), std::string::npos) << r.output;
  r = run("plot '" + root_.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no time_series.csv"), std::string::npos) << r.output;
}

TEST_F(PlotCommand, ABrokenCsvIsNamedWithItsLineNotATraceback) {
  // Issue 22: a broken time_series.csv gave a Python traceback (or was drawn without a
  // word). Each case: one line "regodem plot: error: FILE:LINE: ...", exit status 2.
  const std::string good = regodem::test::read_file(root_ / "sieve" / "time_series.csv");
  const std::size_t header_end = good.find('\n') + 1;
  const std::size_t row2_end = good.find('\n', good.find('\n', header_end) + 1) + 1;  // header + 2 rows
  const std::string header = good.substr(0, header_end);
  const std::string first_rows = good.substr(0, row2_end);
  const std::string rest = good.substr(row2_end);
  std::string bad_cell = rest.substr(0, rest.find('\n'));
  bad_cell.replace(0, bad_cell.find(','), "abc");  // the time of the fourth line
  struct Case {
    const char* name;
    std::string content;
    std::string where;  // ":LINE:" expected in the message
    const char* what;   // a word the message must hold
  };
  const std::vector<Case> cases = {
      {"truncated_row", first_rows + rest.substr(0, 25) + "\n" + rest, ":4:", "fields"},
      {"non_numeric", first_rows + bad_cell + "\n" + rest.substr(rest.find('\n') + 1), ":4:", "abc"},
      {"no_header", good.substr(header_end), ":1:", "header"},
      {"empty", "", ":1:", "empty"},
      {"not_text", header + "0,\xff\xfe\n", ":2:", "UTF-8"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path dir = root_ / ("broken_" + std::string(c.name));
    fs::create_directories(dir);
    {
      std::ofstream csv(dir / "time_series.csv", std::ios::binary);
      csv << c.content;
    }
    const Result r = run("plot '" + dir.string() + "' --out '" + (dir / "plots").string() + "'");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    const std::string expected = "regodem plot: error: " + (dir / "time_series.csv").string() + c.where;
    EXPECT_NE(r.output.find(expected), std::string::npos) << "expected '" << expected << "' in\n" << r.output;
    EXPECT_NE(r.output.find(c.what), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Traceback"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line:\n" << r.output;
  }
}

TEST_F(PlotCommand, ARowStillBeingWrittenIsLeftOutWithANote) {
  // A run in progress may be caught mid-row: a last line without its newline is not an
  // error; it is left out and the command says so.
  const std::string good = regodem::test::read_file(root_ / "sieve" / "time_series.csv");
  const fs::path dir = root_ / "in_progress";
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "time_series.csv", std::ios::binary);
    csv << good << good.substr(good.find('\n') + 1, 30);
  }
  const Result r = run("plot '" + dir.string() + "' --out '" + (dir / "plots").string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("left out"), std::string::npos) << r.output;
  EXPECT_TRUE(png_size(dir / "plots" / "temperature.png").valid) << r.output;
}

TEST_F(PlotCommand, ReadsColumnsWhoseNamesHoldBrackets) {
  // A sieve's segments are "sieve[1]", "sieve[2]", ...: the unit is the last [...] of a
  // column's name (they were read as one column "sieve", and no wall figure was drawn).
  const fs::path dir = root_ / "brackets";
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "time_series.csv");
    csv << "time [s],sieve[1].temperature [K],sieve[2].temperature [K]\n0,100,120\n1,150,130\n2,180,140\n";
  }
  const Result r = run("plot '" + dir.string() + "' --out '" + (dir / "plots").string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(png_size(dir / "plots" / "wall_temperatures.png").valid) << r.output;
}

// Issue 22: a run with heat.time_scale_factor S != 1 is drawn against real time (its
// real_time column, time x S) and the command says so; a run with S = 1 against time.
TEST_F(PlotCommand, ACompressedRunIsDrawnAgainstRealTime) {
  const fs::path dir = root_ / "compressed";
  fs::create_directories(dir / "regions");
  {
    std::ofstream csv(dir / "time_series.csv");
    csv << "time [s],real_time [s],stage [-],kinetic_energy [J],coordination_number [-],temperature_mean [K],"
           "temperature_min [K],temperature_max [K]\n"
           "0,0,0,1,0,100,90,110\n0.5,5,0,0.5,2,120,100,140\n1,10,1,0.1,3,150,120,180\n";
    std::ofstream region(dir / "regions" / "zone.csv");
    region << "time [s],real_time [s],temperature_mean [K],count [-]\n0,0,100,3\n1,10,150,3\n";
  }
  const Result r = run("plot '" + dir.string() + "' --out '" + (dir / "plots").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("time axes in real time: the simulated time x heat.time_scale_factor S = 10"),
            std::string::npos)
      << r.output;
  for (const char* name : {"temperature.png", "mechanics.png", "regions_zone.png"}) {
    const PngSize size = png_size(dir / "plots" / name);
    EXPECT_TRUE(size.valid) << name << "\n" << r.output;
    EXPECT_EQ(size.width, kFigureWidth) << name;
    EXPECT_EQ(size.height, kFigureHeight) << name;
  }
  // The fixture's runs have S = 1 (their real_time equals time): no note.
  const Result plain = run("plot '" + (root_ / "sieve").string() + "' --out '" + (dir / "plain").string() + "'");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(plain.output.find("real time"), std::string::npos) << plain.output;
}

TEST_F(PlotCommand, ASectionNeedsSnapshots) {
  const fs::path bare = root_ / "bare";
  fs::create_directories(bare);
  fs::copy_file(root_ / "sieve" / "time_series.csv", bare / "time_series.csv");
  const Result r = run("plot '" + bare.string() + "' --section");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("output.snapshots"), std::string::npos) << r.output;
}

}  // namespace

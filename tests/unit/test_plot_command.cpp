// `regodem plot`, run as a user runs it on a small run's outputs: PNG files of the
// documented size (read from the PNG header), overlays with labels, the section image,
// and clear refusals of bad arguments.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

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

TEST_F(PlotCommand, ASectionNeedsSnapshots) {
  const fs::path bare = root_ / "bare";
  fs::create_directories(bare);
  fs::copy_file(root_ / "sieve" / "time_series.csv", bare / "time_series.csv");
  const Result r = run("plot '" + bare.string() + "' --section");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("output.snapshots"), std::string::npos) << r.output;
}

}  // namespace

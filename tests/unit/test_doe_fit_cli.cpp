// `regodem doe ccd` and `regodem fit`, run as a user runs them: the design CSV, the fit
// report and its JSON, the solve of the paper's equations end to end, and the refusals
// of bad input (exit status 2 with a message).
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "io/csv_table_reader.hpp"

namespace {

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;
  std::string output;
};

std::string quoted(const std::string& text) {
  std::string q = "'";
  for (const char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs regodem; `stdout_only` leaves stderr out of the captured text.
Result run(const std::vector<std::string>& arguments, bool stdout_only = false) {
  std::string command = quoted(REGODEM_BINARY);
  for (const std::string& a : arguments) command += " " + quoted(a);
  command += stdout_only ? " </dev/null 2>/dev/null" : " </dev/null 2>&1";
  Result result;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) result.output.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class DoeFitCli : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 fmt::format("regodem_doe_cli_{}_{}", ::getpid(),
                             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }
  fs::path file(const std::string& name) const { return directory_ / name; }
  void write(const std::string& name, const std::string& text) const { std::ofstream(file(name)) << text; }

  fs::path directory_;
};

const std::vector<std::string> paper_ccd = {"doe", "ccd", "--factor", "C_wall [J/(kg K)]=1200:600", "--factor",
                                            "lambda_wall [W/(m K)]=300:200", "--centre-points", "3"};

TEST_F(DoeFitCli, CcdWritesThePapersDesign) {
  std::vector<std::string> arguments = paper_ccd;
  arguments.insert(arguments.end(), {"-o", file("design.csv").string()});
  const Result result = run(arguments);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "11 runs")) << result.output;
  const regodem::CsvTable table = regodem::read_csv_table(file("design.csv").string());
  EXPECT_EQ(table.names, (std::vector<std::string>{"run", "std_order", "point_type", "C_wall_coded",
                                                   "lambda_wall_coded", "C_wall", "lambda_wall"}));
  EXPECT_EQ(table.units[5], "J/(kg K)");
  ASSERT_EQ(table.rows.size(), 11U);
  const std::vector<double> c = table.numbers("C_wall"), coded = table.numbers("C_wall_coded");
  EXPECT_EQ(table.rows[0][2], "factorial");
  EXPECT_EQ(table.rows[10][2], "centre");
  EXPECT_EQ(coded[5], std::sqrt(2.0));  // exact through the CSV: shortest round-trip text
  EXPECT_NEAR(c[4], 351.0, 1.0);        // −α, Table 4
  EXPECT_NEAR(c[5], 2048.0, 1.0);       // +α

  // Without -o the CSV goes to standard output, the summary to standard error.
  const Result to_stdout = run(paper_ccd, true);
  ASSERT_EQ(to_stdout.exit_code, 0);
  EXPECT_EQ(to_stdout.output.substr(0, 9), "run,std_o");
  std::ifstream written(file("design.csv"));
  EXPECT_EQ(to_stdout.output, std::string(std::istreambuf_iterator<char>(written), {}));

  std::vector<std::string> random = paper_ccd;
  random.insert(random.end(), {"--order", "random", "--seed", "7"});
  EXPECT_EQ(run(random, true).output, run(random, true).output);
  EXPECT_NE(run(random, true).output, to_stdout.output);
}

TEST_F(DoeFitCli, CcdRefusesBadInput) {
  for (const auto& [arguments, expected] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"doe", "ccd", "--factor", "C_wall=1200"}, "NAME=CENTRE:STEP"},
           {{"doe", "ccd", "--factor", "C_wall=abc:600"}, "is not a number"},
           {{"doe", "ccd", "--factor", "C_wall=1200:-5"}, "must be > 0"},
           {{"doe", "ccd", "--factor", "A=0:1", "--alpha", "wide"}, "--alpha"},
           {{"doe", "ccd", "--factor", "A=0:1", "--factor", "A=1:1"}, "named twice"},
           {{"doe", "ccd", "--factor", "A=0:1", "--half-fraction"}, "at least 5 factors"},
           {{"doe", "ccd", "--factor", "A=0:1", "-o", "/nonexistent/dir/d.csv"}, "cannot write"},
       }) {
    const Result result = run(arguments);
    EXPECT_EQ(result.exit_code, 2) << arguments[3] << ": " << result.output;
    EXPECT_TRUE(contains(result.output, expected)) << result.output;
  }
}

// Montgomery, Design and Analysis of Experiments, Example 11.2 (the same data and numpy/scipy
// reference as tests/unit/test_response_surface.cpp).
const std::string montgomery_csv =
    "x1,x2,yield [%]\n-1,-1,76.5\n-1,1,77.0\n1,-1,78.0\n1,1,79.5\n0,0,79.9\n0,0,80.3\n0,0,80.0\n0,0,79.7\n"
    "0,0,79.8\n1.414,0,78.4\n-1.414,0,75.6\n0,1.414,78.5\n0,-1.414,77.0\n";

TEST_F(DoeFitCli, FitReportsAndWritesJson) {
  write("runs.csv", montgomery_csv);
  const Result result = run({"fit", file("runs.csv").string(), "--factors", "x1,x2", "--response", "yield", "--json",
                             file("fit.json").string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "Response yield [%]: 13 runs, 6 terms")) << result.output;
  EXPECT_TRUE(contains(result.output, "R² 0.9827")) << result.output;
  EXPECT_TRUE(contains(result.output, "lack of fit")) << result.output;
  std::ifstream in(file("fit.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  const auto& response = j.at("responses").at(0);
  EXPECT_EQ(response.at("unit"), "%");
  EXPECT_NEAR(response.at("r_squared").get<double>(), 0.9827306765050124, 1e-12);
  EXPECT_NEAR(response.at("predicted_r_squared").get<double>(), 0.918120752924324, 1e-11);
  EXPECT_NEAR(response.at("coefficients").at(4).at("estimate").get<double>(), -1.3764492825947632, 1e-11);
  EXPECT_EQ(response.at("anova").at(7).at("source"), "lack of fit");
  EXPECT_NEAR(response.at("anova").at(7).at("p_value").get<double>(), 0.2885639882336163, 1e-10);
  EXPECT_EQ(j.at("factors").at(0).at("high"), 1.414);

  // A reduced model through --terms.
  const Result reduced =
      run({"fit", file("runs.csv").string(), "--factors", "x1,x2", "--response", "yield", "--terms", "x1,x2,x1^2"});
  ASSERT_EQ(reduced.exit_code, 0) << reduced.output;
  EXPECT_TRUE(contains(reduced.output, "13 runs, 4 terms")) << reduced.output;
}

/// The paper's CCD with T_d and T_in computed from Eq. 6 and 7 themselves: the fit must give
/// the equations back, and the solve the values the equations imply.
std::string paper_equation_runs() {
  std::string csv = "C_wall [J/(kg K)],lambda_wall [W/(m K)],T_d [K],T_in [K]\n";
  const double a = std::sqrt(2.0);
  const std::vector<std::pair<double, double>> coded = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}, {-a, 0}, {a, 0},
                                                        {0, -a},  {0, a},  {0, 0},  {0, 0}, {0, 0}};
  for (const auto& [u, v] : coded) {
    const double c = 1200 + 600 * u, l = 300 + 200 * v;
    const double td = 195.03231 + 0.001741 * c - 0.883485 * l + 0.001094 * l * l;
    const double tin = 539.60656 - 0.041123 * c - 0.383554 * l + 0.000471 * l * l;
    csv += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", c, l, td, tin);
  }
  return csv;
}

TEST_F(DoeFitCli, SolvesThePapersEquationsSequentiallyAndTogether) {
  write("runs.csv", paper_equation_runs());
  const std::vector<std::string> fit = {"fit",     file("runs.csv").string(), "--factors", "C_wall,lambda_wall",
                                        "--terms", "C_wall,lambda_wall,lambda_wall^2", "--response", "T_d",
                                        "--response", "T_in"};
  std::vector<std::string> sequential = fit;
  sequential.insert(sequential.end(), {"--solve", "T_d=92.4", "--fix", "C_wall=1200", "--then", "T_in=446.8", "--json",
                                       file("solve.json").string()});
  const Result result = run(sequential);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "OUTSIDE the design range")) << result.output;
  EXPECT_TRUE(contains(result.output, "warning: root 2 lies outside the design range")) << result.output;
  std::ifstream in(file("solve.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  const auto& solutions = j.at("solve").at("solutions");
  ASSERT_EQ(solutions.size(), 2U);
  EXPECT_TRUE(solutions[0].at("inside_design_range").get<bool>());
  EXPECT_NEAR(solutions[0].at("factors").at("lambda_wall").get<double>(), 144.32541452906528, 1e-6);
  EXPECT_NEAR(solutions[0].at("factors").at("C_wall").get<double>(), 1149.2551044943584, 1e-5);
  EXPECT_NEAR(solutions[0].at("responses").at("T_in").get<double>(), 446.8, 1e-8);
  EXPECT_FALSE(solutions[1].at("inside_design_range").get<bool>());
  EXPECT_EQ(solutions[1].at("outside").at(0), "lambda_wall");

  std::vector<std::string> together = fit;
  together.insert(together.end(), {"--solve", "T_d=92.4,T_in=446.8", "--json", file("together.json").string()});
  const Result both = run(together);
  ASSERT_EQ(both.exit_code, 0) << both.output;
  std::ifstream in2(file("together.json"));
  const nlohmann::json j2 = nlohmann::json::parse(in2);
  const auto& roots = j2.at("solve").at("solutions");
  ASSERT_EQ(roots.size(), 2U);
  EXPECT_NEAR(roots[1].at("factors").at("C_wall").get<double>(), 1150.17510646, 1e-3);  // scipy fsolve
  EXPECT_NEAR(roots[1].at("factors").at("lambda_wall").get<double>(), 144.17265874, 1e-4);
  EXPECT_TRUE(roots[1].at("inside_design_range").get<bool>());
}

TEST_F(DoeFitCli, FitRefusesBadInput) {
  write("runs.csv", montgomery_csv);
  write("four.csv", "A,B,y\n-1,-1,1\n1,-1,2\n-1,1,3\n1,1,5\n");
  write("factorial.csv", "A,B,y\n-1,-1,1\n1,-1,2\n-1,1,3\n1,1,5\n0,0,2\n0,0,2.1\n0,0,1.9\n");
  write("text.csv", "A,B,y\n-1,-1,1\n1,-1,two\n");
  write("ragged.csv", "A,B,y\n-1,-1,1\n1,-1\n");
  const std::string runs = file("runs.csv").string();
  for (const auto& [arguments, expected] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"fit", runs, "--factors", "x1,x3", "--response", "yield"}, "no column 'x3'"},
           {{"fit", runs, "--factors", "x1,x2", "--response", "strength"}, "no column 'strength'"},
           {{"fit", runs, "--factors", "x1,x2", "--response", "yield", "--terms", "x1,x4"}, "not a factor"},
           {{"fit", file("four.csv").string(), "--factors", "A,B", "--response", "y"}, "4 runs for 6 terms"},
           {{"fit", file("factorial.csv").string(), "--factors", "A,B", "--response", "y"}, "singular design"},
           {{"fit", file("text.csv").string(), "--factors", "A,B", "--response", "y", "--terms", "A"},
            "'two' is not a number"},
           {{"fit", file("ragged.csv").string(), "--factors", "A,B", "--response", "y"}, "2 values"},
           {{"fit", runs, "--factors", "x1,x2", "--response", "yield", "--solve", "yield=80"}, "--fix"},
           {{"fit", runs, "--factors", "x1,x2", "--response", "yield", "--solve", "purity=80", "--fix", "x1=0"},
            "not a fitted response"},
           {{"fit", runs, "--factors", "x1,x2", "--response", "yield", "--solve", "yield=80", "--fix", "x9=0"},
            "not one of the factors"},
           {{"fit", runs, "--factors", "x1,x2", "--response", "yield", "--fix", "x1=0"}, "go with --solve"},
           {{"fit", runs, "--factors", "x1,x2", "--response", "yield", "--terms", "purity=x1"}, "not a fitted response"},
       }) {
    const Result result = run(arguments);
    EXPECT_EQ(result.exit_code, 2) << arguments.back() << ": " << result.output;
    EXPECT_TRUE(contains(result.output, expected)) << result.output;
  }
}

}  // namespace

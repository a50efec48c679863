// `regodem info` and `regodem --version`: what this build is, for bug reports and for
// comparing benchmark numbers between machines.
#include <omp.h>

#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/version.h>

#include "commands.hpp"
#include "regodem/build_info.hpp"

namespace regodem::app {
namespace {

/// FMT_VERSION is major * 10000 + minor * 100 + patch.
std::string fmt_version() {
  return fmt::format("{}.{}.{}", FMT_VERSION / 10000, FMT_VERSION / 100 % 100, FMT_VERSION % 100);
}

/// _OPENMP is the yyyymm date of the specification the compiler implements.
std::string openmp_specification() {
  switch (_OPENMP) {
    case 201511: return "4.5";
    case 201811: return "5.0";
    case 202011: return "5.1";
    case 202111: return "5.2";
    default: return fmt::format("of {}", _OPENMP);
  }
}

}  // namespace

std::string version_line() { return fmt::format("regodem {}", build_info::version); }

int print_info() {
  fmt::print("regodem {}\n", build_info::version);
  fmt::print("build type:     {}\n", build_info::build_type);
  fmt::print("compiler:       {}\n", build_info::compiler);
  fmt::print("OpenMP:         {} threads by default ({} processors), specification {}\n",
             omp_get_max_threads(), omp_get_num_procs(), openmp_specification());
  fmt::print("libraries:      fmt {}, spdlog {}.{}.{}, Eigen {}.{}.{}, CLI11 {}, nlohmann-json {}.{}.{}, "
             "yaml-cpp (version not exposed by its headers)\n",
             fmt_version(), SPDLOG_VER_MAJOR, SPDLOG_VER_MINOR, SPDLOG_VER_PATCH,
             EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION, CLI11_VERSION,
             NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR, NLOHMANN_JSON_VERSION_PATCH);
  return exit_status::success;
}

}  // namespace regodem::app

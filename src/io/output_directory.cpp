#include "io/output_directory.hpp"

#include <system_error>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

bool is_safe_path_character(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
         c == '_' || c == '.';
}

/// Whether a run may write into an existing directory; false: it does not exist yet.
bool exists_and_is_usable(const fs::path& directory, bool overwrite) {
  std::error_code error;
  const fs::file_status status = fs::status(directory, error);
  if (!fs::exists(status)) return false;
  if (!fs::is_directory(status)) {
    throw InputError(fmt::format("output path '{}' exists and is not a directory", directory.string()));
  }
  const bool empty = fs::is_empty(directory, error);
  if (error) {
    throw InputError(fmt::format("cannot read output directory '{}': {}", directory.string(),
                                 error.message()));
  }
  if (!empty && !overwrite) {
    throw InputError(fmt::format(
        "output directory '{}' is not empty; choose another with -o OUTDIR, or pass --overwrite "
        "to replace the outputs of a previous run there",
        directory.string()));
  }
  return true;
}

}  // namespace

std::filesystem::path default_output_directory(std::string_view scenario_name) {
  std::string folder;
  for (const char c : scenario_name) folder += is_safe_path_character(c) ? c : '_';
  // "", "." and ".." would name the output root itself or its parent.
  if (folder.find_first_not_of('.') == std::string::npos) folder = "scenario" + folder;
  return fs::path("out") / folder;
}

void check_output_directory(const std::filesystem::path& directory, bool overwrite) {
  exists_and_is_usable(directory, overwrite);
}

void prepare_output_directory(const std::filesystem::path& directory, bool overwrite,
                              const std::vector<std::string>& run_output_names) {
  std::error_code error;
  if (!exists_and_is_usable(directory, overwrite)) {
    fs::create_directories(directory, error);
    if (error) {
      throw InputError(fmt::format("cannot create output directory '{}': {}", directory.string(),
                                   error.message()));
    }
    return;
  }
  for (const std::string& name : run_output_names) {
    fs::remove_all(directory / name, error);
    if (error) {
      throw InputError(fmt::format("cannot remove '{}' to overwrite it: {}",
                                   (directory / name).string(), error.message()));
    }
  }
}

}  // namespace regodem

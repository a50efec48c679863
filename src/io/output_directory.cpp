#include "io/output_directory.hpp"

#include <algorithm>
#include <system_error>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/run_directory_lock.hpp"

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
  // The lock of the process that is preparing this directory does not count.
  bool empty = true;
  for (fs::directory_iterator entry(directory, error), end; !error && entry != end; entry.increment(error))
    if (entry->path().filename() != RunDirectoryLock::file_name) empty = false;
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

/// Whether `path` is `container` or lies inside it (both canonical).
bool is_within(const fs::path& path, const fs::path& container) {
  const auto [mismatch, unused] = std::mismatch(container.begin(), container.end(), path.begin(), path.end());
  return mismatch == container.end();
}

/// The path with symbolic links and ".." resolved, for as much of it as exists.
fs::path resolved(const fs::path& path) {
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(path, error);
  return error ? fs::absolute(path).lexically_normal() : canonical;
}

/// Whether a file in an output folder has the form of one a run writes there: a
/// snapshot (.vtp), a measurement (.csv), a checkpoint (.rgck), or the temporary file
/// of an atomic write that a killed run left (".NAME.tmp-...").
bool is_written_by_a_run(const fs::path& file) {
  const std::string name = file.filename().string();
  const std::string extension = file.extension().string();
  return extension == ".vtp" || extension == ".csv" || extension == ".rgck" ||
         (name.starts_with('.') && name.find(".tmp-") != std::string::npos);
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

std::vector<std::filesystem::path> prepare_output_directory(const std::filesystem::path& directory, bool overwrite,
                                                            const std::vector<std::string>& run_output_names) {
  std::error_code error;
  if (!exists_and_is_usable(directory, overwrite)) {
    fs::create_directories(directory, error);
    if (error) {
      throw InputError(fmt::format("cannot create output directory '{}': {}", directory.string(),
                                   error.message()));
    }
    return {};
  }
  std::vector<fs::path> kept;
  const auto remove = [&](const fs::path& path) {
    fs::remove(path, error);
    if (error)
      throw InputError(fmt::format("cannot remove '{}' to overwrite it: {}", path.string(), error.message()));
  };
  for (const std::string& name : run_output_names) {
    const fs::path path = directory / name;
    if (!fs::is_directory(fs::symlink_status(path, error))) {
      remove(path);
      continue;
    }
    // An output folder (vtk/, checkpoints/...): only what a run writes there goes, so
    // that a user's own file in it survives --overwrite.
    std::vector<fs::path> entries;
    for (fs::directory_iterator entry(path, error), end; !error && entry != end; entry.increment(error))
      entries.push_back(entry->path());
    if (error)
      throw InputError(fmt::format("cannot read '{}' to overwrite it: {}", path.string(), error.message()));
    for (const fs::path& entry : entries) {
      if (is_written_by_a_run(entry) && !fs::is_directory(fs::symlink_status(entry, error)))
        remove(entry);
      else
        kept.push_back(entry);
    }
    if (fs::is_empty(path, error)) remove(path);
  }
  return kept;
}

void check_inputs_outside_outputs(const std::filesystem::path& directory,
                                  const std::vector<std::string>& run_output_names,
                                  const std::vector<std::filesystem::path>& inputs) {
  const fs::path output_root = resolved(directory);
  for (const fs::path& input : inputs) {
    // The file itself, and (for a link among the outputs, which --overwrite removes) the
    // link.
    const fs::path absolute_input = fs::absolute(input).lexically_normal();
    const fs::path spellings[] = {resolved(input),
                                  resolved(absolute_input.parent_path()) / absolute_input.filename()};
    for (const std::string& name : run_output_names) {
      const fs::path output = output_root / name;
      if (!is_within(spellings[0], output) && !is_within(spellings[1], output)) continue;
      throw InputError(fmt::format(
          "{}: this run reads it, and it is among the outputs the run writes in '{}' ('{}'), which the run would "
          "delete or overwrite: choose another output directory with -o OUTDIR, or copy the input out of '{}' "
          "and run from the copy",
          input.string(), directory.string(), name, directory.string()));
    }
  }
}

}  // namespace regodem

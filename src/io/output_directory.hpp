#pragma once
// Where a run writes its outputs, and the rule that one run never silently mixes its
// files with another's: a non-empty directory is refused unless the user says
// --overwrite.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace regodem {

/// "out/<scenario name>", relative to the working directory; characters that are
/// awkward in a path (separators, spaces, quotes...) become '_'.
std::filesystem::path default_output_directory(std::string_view scenario_name);

/// Throws InputError if prepare_output_directory would refuse `directory` (not a
/// directory; not empty without `overwrite`), changing nothing: a run checks this
/// before its slower preparations.
void check_output_directory(const std::filesystem::path& directory, bool overwrite);

/// Makes `directory` ready for a run. A missing directory is created (with its
/// parents); an empty one is used as it is. A non-empty one is refused with an
/// InputError unless `overwrite`; then only the entries named in `run_output_names`
/// (the files and folders a run writes) are removed, and inside such a folder only
/// the files of the forms a run writes there (.vtp, .csv, .rgck, leftover temporary
/// files), the folder itself when that empties it: --overwrite must never delete
/// files a run did not write, as `-o .` would otherwise do. Returns what it kept
/// inside the output folders. Throws InputError when the path is not a directory or
/// cannot be created.
std::vector<std::filesystem::path> prepare_output_directory(const std::filesystem::path& directory, bool overwrite,
                                                            const std::vector<std::string>& run_output_names);

/// Throws InputError, naming the input, when one of `inputs` (the files and folders a
/// run reads: its scenario, meshes, particle files, the checkpoints it starts from) is
/// one of the entries `run_output_names` of `directory` or lies inside one: the run
/// would delete it (--overwrite) or write over it. Paths are compared after resolving
/// symbolic links and "..", so another spelling of the same file is found too.
void check_inputs_outside_outputs(const std::filesystem::path& directory,
                                  const std::vector<std::string>& run_output_names,
                                  const std::vector<std::filesystem::path>& inputs);

}  // namespace regodem

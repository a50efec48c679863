#pragma once
// "Outputs are written whole": whoever reads an output (a plot script, ParaView, a
// later `regodem` command) sees either the previous file or the complete new one,
// never a half-written file, even if the run is killed while writing.
#include <filesystem>
#include <string_view>

namespace regodem {

/// Writes `content` to a temporary file beside `path`, flushes it to disk and renames
/// it over `path` (atomic on POSIX within one file system). Throws std::system_error
/// naming the file on failure; the temporary file is removed then.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// Copies `source` to `destination` with write_file_atomically.
void copy_file_atomically(const std::filesystem::path& source,
                          const std::filesystem::path& destination);

}  // namespace regodem

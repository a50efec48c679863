#include "checkpoint_keeper.hpp"

#include <algorithm>
#include <cstdlib>

#include <fmt/format.h>

namespace regodem::app {
namespace {

namespace fs = std::filesystem;

constexpr const char* kIdentity = "RUNI";
constexpr const char* kPrefix = "checkpoint_";
constexpr const char* kExtension = ".rgck";

/// The number in "checkpoint_NNNNNN.rgck", or 0 for another name.
unsigned number_of(const fs::path& file) {
  const std::string name = file.filename().string();
  if (!name.starts_with(kPrefix) || !name.ends_with(kExtension)) return 0;
  const std::string digits = name.substr(std::string(kPrefix).size(),
                                         name.size() - std::string(kPrefix).size() - std::string(kExtension).size());
  if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return 0;
  return static_cast<unsigned>(std::strtoul(digits.c_str(), nullptr, 10));
}

}  // namespace

void save_identity(Checkpoint& checkpoint, const RunIdentity& identity) {
  ByteWriter w;
  w.put_string(identity.scenario_path);
  w.put(static_cast<std::uint64_t>(identity.overrides.size()));
  for (const std::string& o : identity.overrides) w.put_string(o);
  w.put_string(identity.content_hash);
  w.put(static_cast<std::int32_t>(identity.threads));
  checkpoint.add(kIdentity, 1, std::move(w));
}

RunIdentity read_identity(const Checkpoint& checkpoint) {
  ByteReader r = checkpoint.reader(kIdentity);
  RunIdentity identity;
  identity.scenario_path = r.get_string();
  identity.overrides.resize(r.get<std::uint64_t>());
  for (std::string& o : identity.overrides) o = r.get_string();
  identity.content_hash = r.get_string();
  identity.threads = r.get<std::int32_t>();
  return identity;
}

std::vector<fs::path> checkpoint_files_newest_first(const fs::path& run_directory) {
  std::vector<fs::path> files;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(run_directory / CheckpointKeeper::folder, error))
    if (entry.is_regular_file() && number_of(entry.path()) > 0) files.push_back(entry.path());
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) { return number_of(a) > number_of(b); });
  return files;
}

CheckpointKeeper::CheckpointKeeper(fs::path run_directory, double every_wall_s)
    : folder_(std::move(run_directory) / folder), every_wall_s_(every_wall_s), last_written_(Clock::now()) {
  for (const fs::path& file : checkpoint_files_newest_first(folder_.parent_path()))
    next_number_ = std::max(next_number_, number_of(file) + 1);
}

bool CheckpointKeeper::due() const {
  return every_wall_s_ > 0.0 &&
         std::chrono::duration<double>(Clock::now() - last_written_).count() >= every_wall_s_;
}

fs::path CheckpointKeeper::write(const Checkpoint& checkpoint) {
  fs::create_directories(folder_);
  const fs::path file = folder_ / fmt::format("{}{:06d}{}", kPrefix, next_number_, kExtension);
  write_checkpoint_file(file, checkpoint);
  ++next_number_;
  last_written_ = Clock::now();
  latest_ = file;
  const std::vector<fs::path> files = checkpoint_files_newest_first(folder_.parent_path());
  for (std::size_t k = 2; k < files.size(); ++k) {
    std::error_code ignored;  // an old checkpoint that will not go away does no harm
    fs::remove(files[k], ignored);
  }
  return file;
}

}  // namespace regodem::app

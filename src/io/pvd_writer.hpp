#pragma once
// A ParaView data collection (.pvd): the list of a series' files with their simulated
// times, which ParaView plays as an animation. It is rewritten whole (temporary file,
// then rename) after every snapshot, so a run stopped at any moment leaves a valid
// collection of the snapshots written so far.
#include <filesystem>
#include <string>
#include <vector>

namespace regodem {

class PvdCollection {
 public:
  struct Entry {
    double time_s = 0.0;
    std::string file;  // relative to the .pvd's folder, '/' separated
  };

  explicit PvdCollection(std::filesystem::path path) : path_(std::move(path)) {}

  /// Adds a data set and rewrites the file. Times must not decrease (ParaView sorts by
  /// time and would hide a data set that repeats one): throws std::invalid_argument.
  void add(double time_s, const std::string& relative_file);

  const std::vector<Entry>& entries() const { return entries_; }
  /// Replaces the entries and rewrites the file (a resumed run: the collection as its
  /// checkpoint knew it).
  void restore(std::vector<Entry> entries);
  const std::filesystem::path& path() const { return path_; }
  /// The file's content for the entries so far.
  std::string to_string() const;

 private:
  std::filesystem::path path_;
  std::vector<Entry> entries_;
};

}  // namespace regodem

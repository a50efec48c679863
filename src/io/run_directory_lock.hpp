#pragma once
// One writer per run directory. A run (or `resume`, or `calibrate`) holds an advisory
// lock on OUTDIR/.regodem-lock for its whole life, so a second process that would write
// into the same directory — a resume beside a live run, two runs started together,
// --overwrite over a live run — is refused instead of corrupting its files. The lock
// is flock(2): the kernel drops it when its process dies, so a killed run's stale file
// does not block the next one.
#include <filesystem>
#include <string>

namespace regodem {

class RunDirectoryLock {
 public:
  /// The lock file's name inside a run directory (not an output: an empty-directory
  /// check looks past it, and --overwrite leaves it).
  static constexpr const char* file_name = ".regodem-lock";

  /// Locks `directory`, creating it (and its parents) when it does not exist. `holder`
  /// says who holds it ("regodem run x.yaml"); it is written into the lock file with
  /// the process id and the time, for the message another process gets. Throws
  /// InputError, naming the holder, when another live process holds the lock, and
  /// when the directory cannot be created or the lock file not written.
  RunDirectoryLock(const std::filesystem::path& directory, const std::string& holder);
  /// Removes the lock file and releases the lock.
  ~RunDirectoryLock();
  RunDirectoryLock(const RunDirectoryLock&) = delete;
  RunDirectoryLock& operator=(const RunDirectoryLock&) = delete;

  /// Whether acquiring the lock created the directory: a run refused before it wrote
  /// anything then removes it again (release_and_remove_created_directory).
  bool created_directory() const { return created_directory_; }

  /// Releases the lock now and, when the lock created the directory and nothing else
  /// was written there since, removes the directory again.
  void release_and_remove_created_directory();

 private:
  void release();

  std::filesystem::path directory_;
  std::filesystem::path file_;
  int descriptor_ = -1;
  bool created_directory_ = false;
};

}  // namespace regodem

#include "io/run_directory_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <system_error>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

std::string read_holder(const fs::path& file) {
  std::ifstream input(file, std::ios::binary);
  std::string text{std::istreambuf_iterator<char>(input), std::istreambuf_iterator<char>()};
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text.empty() ? std::string("another process (it has not said which yet)") : text;
}

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

/// Whether `descriptor` is still the file at `path`: a holder removes the file as it
/// releases the lock, so a process that opened the old file before that and then got
/// its lock must open the path again.
bool is_the_file_at(int descriptor, const fs::path& path) {
  struct stat opened {}, named {};
  if (::fstat(descriptor, &opened) != 0 || ::stat(path.c_str(), &named) != 0) return false;
  return opened.st_dev == named.st_dev && opened.st_ino == named.st_ino;
}

}  // namespace

RunDirectoryLock::RunDirectoryLock(const fs::path& directory, const std::string& holder)
    : directory_(directory), file_(directory / file_name) {
  std::error_code error;
  const fs::file_status status = fs::status(directory, error);
  if (fs::exists(status) && !fs::is_directory(status))
    throw InputError(fmt::format("output path '{}' exists and is not a directory", directory.string()));
  if (!fs::exists(status)) {
    created_directory_ = fs::create_directories(directory, error);
    if (error)
      throw InputError(
          fmt::format("cannot create output directory '{}': {}", directory.string(), error.message()));
  }
  while (true) {
    descriptor_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (descriptor_ < 0) {
      const int code = errno;
      if (created_directory_) fs::remove(directory_, error);
      throw InputError(fmt::format("cannot write in output directory '{}': {}", directory.string(),
                                   std::strerror(code)));
    }
    if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
      const int code = errno;
      ::close(descriptor_);
      descriptor_ = -1;
      if (code == EWOULDBLOCK)
        throw InputError(fmt::format(
            "output directory '{}' is in use by {}; a second process writing there would corrupt its files. Wait "
            "for it to end, or choose another directory with -o OUTDIR",
            directory.string(), read_holder(file_)));
      throw InputError(fmt::format("cannot lock output directory '{}': {}", directory.string(),
                                   std::strerror(code)));
    }
    if (is_the_file_at(descriptor_, file_)) break;
    ::close(descriptor_);  // the previous holder removed it as we opened it: again
    descriptor_ = -1;
  }
  const std::string text = fmt::format("pid {} ({}), since {}\n", ::getpid(), holder, utc_now());
  if (::ftruncate(descriptor_, 0) != 0 ||
      ::write(descriptor_, text.data(), text.size()) != static_cast<ssize_t>(text.size())) {
    const int code = errno;
    release_and_remove_created_directory();
    throw InputError(fmt::format("cannot write the lock file in output directory '{}': {}", directory.string(),
                                 std::strerror(code)));
  }
}

RunDirectoryLock::~RunDirectoryLock() { release(); }

void RunDirectoryLock::release() {
  if (descriptor_ < 0) return;
  // Removed while still held, so that no other process can lock the old file for good.
  ::unlink(file_.c_str());
  ::close(descriptor_);
  descriptor_ = -1;
}

void RunDirectoryLock::release_and_remove_created_directory() {
  release();
  if (!created_directory_) return;
  std::error_code error;
  if (fs::is_empty(directory_, error) && !error) fs::remove(directory_, error);
  created_directory_ = false;
}

}  // namespace regodem

#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include <fmt/format.h>

namespace regodem {
namespace {

[[noreturn]] void throw_errno(int error, const std::string& what) {
  throw std::system_error(error, std::generic_category(), what);
}

/// A name no other writer uses: the process id tells processes apart, the counter
/// threads and successive writes of one process.
std::filesystem::path temporary_path_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  const std::string name = fmt::format(".{}.tmp-{}-{}", path.filename().string(),
                                       static_cast<long>(::getpid()), counter.fetch_add(1));
  return path.parent_path() / name;
}

/// Closes and removes the temporary file unless the rename went through.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::filesystem::path path) : path_(std::move(path)) {
    descriptor_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor_ < 0) throw_errno(errno, fmt::format("cannot create '{}'", path_.string()));
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (descriptor_ >= 0) ::close(descriptor_);
    if (!renamed_) ::unlink(path_.c_str());
  }

  void write_all(std::string_view content) {
    while (!content.empty()) {
      const ssize_t written = ::write(descriptor_, content.data(), content.size());
      if (written < 0) {
        if (errno == EINTR) continue;
        throw_errno(errno, fmt::format("cannot write '{}'", path_.string()));
      }
      content.remove_prefix(static_cast<std::size_t>(written));
    }
  }

  /// fsync before rename: otherwise a crash soon after could leave the new name
  /// pointing at an empty file on file systems that delay allocation.
  void sync_and_close() {
    if (::fsync(descriptor_) != 0) throw_errno(errno, fmt::format("cannot sync '{}'", path_.string()));
    const int descriptor = descriptor_;
    descriptor_ = -1;
    if (::close(descriptor) != 0) throw_errno(errno, fmt::format("cannot close '{}'", path_.string()));
  }

  void rename_to(const std::filesystem::path& destination) {
    if (::rename(path_.c_str(), destination.c_str()) != 0) {
      throw_errno(errno, fmt::format("cannot rename '{}' to '{}'", path_.string(),
                                     destination.string()));
    }
    renamed_ = true;
  }

 private:
  std::filesystem::path path_;
  int descriptor_ = -1;
  bool renamed_ = false;
};

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  TemporaryFile temporary(temporary_path_beside(path));
  temporary.write_all(content);
  temporary.sync_and_close();
  temporary.rename_to(path);
}

void copy_file_atomically(const std::filesystem::path& source,
                          const std::filesystem::path& destination) {
  std::ifstream input(source, std::ios::binary);
  if (!input) throw_errno(errno, fmt::format("cannot read '{}'", source.string()));
  const std::string content{std::istreambuf_iterator<char>(input), std::istreambuf_iterator<char>()};
  if (input.bad()) throw_errno(errno, fmt::format("cannot read '{}'", source.string()));
  write_file_atomically(destination, content);
}

}  // namespace regodem

// write_file_atomically: the file appears whole, replaces the old one by rename (a
// reader of the old file keeps the old content), and no temporary file stays behind.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

#include "io/atomic_file.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "regodem-atomic-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    directory_ = pattern;
  }
  void TearDown() override { fs::remove_all(directory_); }

  static std::string read_all(const fs::path& path) {
    std::ifstream input(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(input), std::istreambuf_iterator<char>()};
  }
  std::size_t entries_in_directory() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(directory_), fs::directory_iterator()));
  }

  fs::path directory_;
};

TEST_F(AtomicFileTest, CreatesFileWithExactContentAndNoTemporaryLeft) {
  const std::string content("line one\nline two\0with a zero byte\n", 35);
  write_file_atomically(directory_ / "out.txt", content);
  EXPECT_EQ(read_all(directory_ / "out.txt"), content);
  EXPECT_EQ(entries_in_directory(), 1u);
}

TEST_F(AtomicFileTest, ReplacesLongerContentWithoutLeftoverBytes) {
  write_file_atomically(directory_ / "out.txt", std::string(10000, 'x'));
  write_file_atomically(directory_ / "out.txt", "short");
  EXPECT_EQ(read_all(directory_ / "out.txt"), "short");
  EXPECT_EQ(entries_in_directory(), 1u);
}

TEST_F(AtomicFileTest, ReaderOfTheOldFileKeepsOldContent) {
  // Rewriting in place would show this reader a truncated or mixed file; a rename
  // leaves it the old one, which is what "written whole" means for readers.
  write_file_atomically(directory_ / "out.txt", "old content");
  std::ifstream old_reader(directory_ / "out.txt", std::ios::binary);
  ASSERT_TRUE(old_reader);
  write_file_atomically(directory_ / "out.txt", "new content, longer than the old");
  const std::string seen_by_old_reader{std::istreambuf_iterator<char>(old_reader),
                                       std::istreambuf_iterator<char>()};
  EXPECT_EQ(seen_by_old_reader, "old content");
  EXPECT_EQ(read_all(directory_ / "out.txt"), "new content, longer than the old");
}

TEST_F(AtomicFileTest, FailureNamesThePathAndLeavesNothing) {
  const fs::path missing_folder = directory_ / "no-such-folder" / "out.txt";
  try {
    write_file_atomically(missing_folder, "content");
    FAIL() << "expected std::system_error";
  } catch (const std::system_error& error) {
    EXPECT_NE(std::string(error.what()).find("no-such-folder"), std::string::npos) << error.what();
  }
  EXPECT_EQ(entries_in_directory(), 0u);
}

TEST_F(AtomicFileTest, RenameOntoADirectoryFailsAndRemovesTheTemporary) {
  fs::create_directory(directory_ / "taken");
  fs::create_directory(directory_ / "taken" / "occupied");  // a non-empty directory cannot be replaced
  EXPECT_THROW(write_file_atomically(directory_ / "taken", "content"), std::system_error);
  EXPECT_EQ(entries_in_directory(), 1u);  // only "taken": the temporary file is gone
}

TEST_F(AtomicFileTest, CopiesAFileAndNamesAMissingSource) {
  write_file_atomically(directory_ / "source.yaml", "name: demo\n");
  copy_file_atomically(directory_ / "source.yaml", directory_ / "copy.yaml");
  EXPECT_EQ(read_all(directory_ / "copy.yaml"), "name: demo\n");
  try {
    copy_file_atomically(directory_ / "absent.yaml", directory_ / "copy2.yaml");
    FAIL() << "expected std::system_error";
  } catch (const std::system_error& error) {
    EXPECT_NE(std::string(error.what()).find("absent.yaml"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(directory_ / "copy2.yaml"));
}

}  // namespace
}  // namespace regodem

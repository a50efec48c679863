// The checkpoint file format (docs/checkpoint-format.md): sections read back as
// written; a flipped byte, a truncated file, another format version or another kind of
// file are refused with a message that names the file and what is wrong.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/checkpoint_file.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

Checkpoint sample_checkpoint() {
  Checkpoint c;
  ByteWriter a;
  a.put(std::uint32_t{7});
  a.put(2.5);
  a.put_vector(std::vector<double>{1.0, -2.0, 3.25});
  a.put_string("grain");
  c.add("AAAA", 1, std::move(a));
  ByteWriter b;
  b.put(std::uint64_t{42});
  c.add("BBBB", 3, std::move(b));
  return c;
}

fs::path temporary_directory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("regodem_checkpoint_" + name + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
}

/// The error message of reading `path`, or "" when it reads.
std::string read_error(const fs::path& path) {
  try {
    read_checkpoint_file(path);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckpointFile, SectionsReadBackAsWritten) {
  const fs::path dir = temporary_directory("roundtrip");
  write_checkpoint_file(dir / "a.ckpt", sample_checkpoint());
  const Checkpoint c = read_checkpoint_file(dir / "a.ckpt");
  ASSERT_EQ(c.sections().size(), 2u);
  ByteReader a = c.reader("AAAA");
  EXPECT_EQ(a.get<std::uint32_t>(), 7u);
  EXPECT_EQ(a.get<double>(), 2.5);
  std::vector<double> v;
  a.get_vector(v);
  EXPECT_EQ(v, (std::vector<double>{1.0, -2.0, 3.25}));
  EXPECT_EQ(a.get_string(), "grain");
  EXPECT_TRUE(a.at_end());
  ByteReader b = c.reader("BBBB", 3);
  EXPECT_EQ(b.get<std::uint64_t>(), 42u);
  EXPECT_THROW(c.reader("BBBB", 2), CheckpointError);  // a newer section layout
  EXPECT_THROW(c.reader("CCCC"), CheckpointError);      // a missing section
  EXPECT_THROW(b.get<double>(), CheckpointError);       // past the section's end
  fs::remove_all(dir);
}

TEST(CheckpointFile, EveryFlippedByteIsRefused) {
  const std::string good = encode_checkpoint(sample_checkpoint());
  for (std::size_t at = 0; at < good.size(); ++at) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x10);
    EXPECT_THROW(decode_checkpoint(bad, "flipped.ckpt"), CheckpointError) << "byte " << at;
  }
}

TEST(CheckpointFile, CorruptFileIsRefusedWithItsNameAndTheReason) {
  const fs::path dir = temporary_directory("corrupt");
  std::string bytes = encode_checkpoint(sample_checkpoint());
  bytes[40] = static_cast<char>(bytes[40] ^ 0x01);  // inside the first section's body
  write_bytes(dir / "bad.ckpt", bytes);
  const std::string message = read_error(dir / "bad.ckpt");
  EXPECT_NE(message.find((dir / "bad.ckpt").string()), std::string::npos) << message;
  EXPECT_NE(message.find("corrupt"), std::string::npos) << message;
  EXPECT_NE(message.find("CRC-32"), std::string::npos) << message;
  fs::remove_all(dir);
}

TEST(CheckpointFile, TruncatedFileIsRefused) {
  const fs::path dir = temporary_directory("truncated");
  const std::string bytes = encode_checkpoint(sample_checkpoint());
  for (const std::size_t keep : {std::size_t{0}, std::size_t{5}, std::size_t{20}, bytes.size() / 2, bytes.size() - 1}) {
    write_bytes(dir / "short.ckpt", bytes.substr(0, keep));
    const std::string message = read_error(dir / "short.ckpt");
    EXPECT_NE(message, "") << keep;
    EXPECT_NE(message.find("short.ckpt"), std::string::npos) << message;
    if (keep >= 24) {
      EXPECT_NE(message.find("truncated"), std::string::npos) << message;
    }
  }
  fs::remove_all(dir);
}

TEST(CheckpointFile, OtherFormatVersionOrOtherFileIsRefused) {
  std::string bytes = encode_checkpoint(sample_checkpoint());
  bytes[8] = 2;  // the format version, right after the magic
  try {
    decode_checkpoint(bytes, "v2.ckpt");
    FAIL();
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("format version 2"), std::string::npos) << e.what();
  }
  try {
    decode_checkpoint("name,x,y\n1,2,3\n", "table.csv");
    FAIL();
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("not a RegoDEM checkpoint"), std::string::npos) << e.what();
  }
  const fs::path dir = temporary_directory("missing");
  EXPECT_NE(read_error(dir / "none.ckpt").find("cannot read"), std::string::npos);
  fs::remove_all(dir);
}

TEST(CheckpointFile, UnknownSectionsAreKeptForLaterReaders) {
  Checkpoint c = sample_checkpoint();
  ByteWriter extra;
  extra.put(1.0);
  c.add("NEWS", 1, std::move(extra));  // state a later version adds
  const Checkpoint back = decode_checkpoint(encode_checkpoint(c), "x");
  EXPECT_EQ(back.reader("AAAA").get<std::uint32_t>(), 7u);
  EXPECT_TRUE(back.has("NEWS"));
}

}  // namespace
}  // namespace regodem

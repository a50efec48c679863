#pragma once
// A checkpoint file (docs/checkpoint-format.md): a header with a magic and the format
// version, tagged and length-prefixed sections, and a CRC-32 over them. New state goes
// into a new section; readers skip sections they do not know, so adding one keeps the
// layout of the others.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "io/checkpoint_bytes.hpp"

namespace regodem {

inline constexpr char kCheckpointMagic[8] = {'R', 'E', 'G', 'O', 'C', 'K', 'P', 'T'};
inline constexpr std::uint32_t kCheckpointFormatVersion = 1;

struct CheckpointSection {
  std::string tag;          // four ASCII characters, e.g. "PART"
  std::uint32_t version = 1;  // of this section's own layout
  std::string body;
};

class Checkpoint {
 public:
  /// Adds a section (a tag may occur once).
  void add(std::string tag, std::uint32_t version, ByteWriter&& body);
  bool has(std::string_view tag) const;
  /// A reader over the section's body; throws CheckpointError when it is missing or of
  /// a newer version than `max_version`.
  ByteReader reader(std::string_view tag, std::uint32_t max_version = 1) const;
  const std::vector<CheckpointSection>& sections() const { return sections_; }
  std::vector<CheckpointSection>& sections() { return sections_; }
  /// The file this came from (error messages), empty for one built in memory.
  std::string source;

 private:
  std::vector<CheckpointSection> sections_;
};

/// The file's bytes: header, sections, CRC.
std::string encode_checkpoint(const Checkpoint& checkpoint);
/// Writes the file whole (temporary file, then rename): a crash while writing leaves
/// the previous file at `path`, if any.
void write_checkpoint_file(const std::filesystem::path& path, const Checkpoint& checkpoint);

/// Parses and checks the bytes; `source` names them in errors. Throws CheckpointError.
Checkpoint decode_checkpoint(std::string_view bytes, const std::string& source);
/// Reads and checks a file: magic, format version, length (truncation), CRC-32 and
/// the section framing. Throws CheckpointError naming the file and what is wrong.
Checkpoint read_checkpoint_file(const std::filesystem::path& path);

}  // namespace regodem

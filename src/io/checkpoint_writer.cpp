#include <zlib.h>

#include <algorithm>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/checkpoint_file.hpp"

namespace regodem {

void Checkpoint::add(std::string tag, std::uint32_t version, ByteWriter&& body) {
  if (tag.size() != 4) throw std::invalid_argument(fmt::format("checkpoint section tag '{}' is not 4 characters", tag));
  if (has(tag)) throw std::invalid_argument(fmt::format("checkpoint section '{}' added twice", tag));
  sections_.push_back({std::move(tag), version, std::move(body.bytes())});
}

bool Checkpoint::has(std::string_view tag) const {
  return std::any_of(sections_.begin(), sections_.end(), [&](const CheckpointSection& s) { return s.tag == tag; });
}

ByteReader Checkpoint::reader(std::string_view tag, std::uint32_t max_version) const {
  for (const CheckpointSection& s : sections_) {
    if (s.tag != tag) continue;
    const std::string what = fmt::format("section '{}' of checkpoint '{}'", tag, source);
    if (s.version > max_version)
      throw CheckpointError(fmt::format("{} has version {}; this regodem reads up to version {}", what, s.version,
                                        max_version));
    return ByteReader(s.body, what);
  }
  throw CheckpointError(fmt::format("checkpoint '{}' has no section '{}'", source, tag));
}

std::string encode_checkpoint(const Checkpoint& checkpoint) {
  ByteWriter payload;
  for (const CheckpointSection& s : checkpoint.sections()) {
    payload.bytes().append(s.tag);
    payload.put(s.version);
    payload.put(static_cast<std::uint64_t>(s.body.size()));
    payload.bytes().append(s.body);
  }
  const std::string& body = payload.bytes();
  ByteWriter file;
  file.bytes().append(kCheckpointMagic, sizeof kCheckpointMagic);
  file.put(kCheckpointFormatVersion);
  file.put(static_cast<std::uint32_t>(checkpoint.sections().size()));
  file.put(static_cast<std::uint64_t>(body.size()));
  file.bytes().append(body);
  // zlib's crc32 takes at most UINT_MAX bytes per call.
  uLong crc = crc32(0L, Z_NULL, 0);
  for (std::size_t at = 0; at < body.size();) {
    const std::size_t chunk = std::min<std::size_t>(body.size() - at, 1u << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(body.data() + at), static_cast<uInt>(chunk));
    at += chunk;
  }
  file.put(static_cast<std::uint32_t>(crc));
  return std::move(file.bytes());
}

void write_checkpoint_file(const std::filesystem::path& path, const Checkpoint& checkpoint) {
  write_file_atomically(path, encode_checkpoint(checkpoint));
}

}  // namespace regodem

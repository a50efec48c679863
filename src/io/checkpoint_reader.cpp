#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "io/checkpoint_file.hpp"

namespace regodem {
namespace {

constexpr std::size_t kHeaderBytes = sizeof kCheckpointMagic + 4 + 4 + 8;
constexpr std::size_t kTrailerBytes = 4;
constexpr std::size_t kSectionHeaderBytes = 4 + 4 + 8;

std::uint32_t crc_of(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t chunk = std::min<std::size_t>(bytes.size() - at, 1u << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), static_cast<uInt>(chunk));
    at += chunk;
  }
  return static_cast<std::uint32_t>(crc);
}

}  // namespace

Checkpoint decode_checkpoint(std::string_view bytes, const std::string& source) {
  const auto fail = [&](const std::string& what) -> CheckpointError {
    return CheckpointError(fmt::format("checkpoint '{}' {}", source, what));
  };
  if (bytes.size() < sizeof kCheckpointMagic || std::memcmp(bytes.data(), kCheckpointMagic, sizeof kCheckpointMagic) != 0)
    throw fail("is not a RegoDEM checkpoint (it does not begin with REGOCKPT)");
  if (bytes.size() < kHeaderBytes) throw fail(fmt::format("is truncated: {} bytes, shorter than its header", bytes.size()));
  ByteReader header(bytes.substr(sizeof kCheckpointMagic, kHeaderBytes - sizeof kCheckpointMagic), "header");
  const auto version = header.get<std::uint32_t>();
  const auto section_count = header.get<std::uint32_t>();
  const auto payload_bytes = header.get<std::uint64_t>();
  if (version != kCheckpointFormatVersion)
    throw fail(fmt::format("has format version {}; this regodem reads version {}", version, kCheckpointFormatVersion));
  const std::size_t available = bytes.size() - kHeaderBytes;
  if (payload_bytes > available || available - payload_bytes < kTrailerBytes)
    throw fail(fmt::format("is truncated: its header announces {} bytes of sections and a 4-byte checksum, the file "
                           "holds {} bytes after the header",
                           payload_bytes, available));
  if (available - payload_bytes != kTrailerBytes)
    throw fail(fmt::format("has {} unexpected bytes after its checksum", available - payload_bytes - kTrailerBytes));
  const std::string_view payload = bytes.substr(kHeaderBytes, payload_bytes);
  std::uint32_t stored_crc;
  std::memcpy(&stored_crc, bytes.data() + kHeaderBytes + payload_bytes, sizeof stored_crc);
  const std::uint32_t crc = crc_of(payload);
  if (crc != stored_crc)
    throw fail(fmt::format("is corrupt: its CRC-32 is {:08x}, the file says {:08x}", crc, stored_crc));

  Checkpoint checkpoint;
  checkpoint.source = source;
  std::size_t at = 0;
  for (std::uint32_t s = 0; s < section_count; ++s) {
    if (payload.size() - at < kSectionHeaderBytes) throw fail(fmt::format("ends inside the header of section {}", s));
    CheckpointSection section;
    section.tag = std::string(payload.substr(at, 4));
    ByteReader framing(payload.substr(at + 4, 12), "section header");
    section.version = framing.get<std::uint32_t>();
    const auto length = framing.get<std::uint64_t>();
    at += kSectionHeaderBytes;
    if (length > payload.size() - at)
      throw fail(fmt::format("section '{}' announces {} bytes, only {} are left", section.tag, length, payload.size() - at));
    section.body = std::string(payload.substr(at, length));
    at += length;
    checkpoint.sections().push_back(std::move(section));
  }
  if (at != payload.size()) throw fail(fmt::format("has {} bytes after its last section", payload.size() - at));
  return checkpoint;
}

Checkpoint read_checkpoint_file(const std::filesystem::path& path) {
  std::ifstream input(path, std::ios::binary);
  if (!input)
    throw CheckpointError(fmt::format("cannot read checkpoint '{}': {}", path.string(), std::strerror(errno)));
  const std::string bytes{std::istreambuf_iterator<char>(input), std::istreambuf_iterator<char>()};
  if (input.bad()) throw CheckpointError(fmt::format("cannot read checkpoint '{}'", path.string()));
  return decode_checkpoint(bytes, path.string());
}

}  // namespace regodem

#pragma once
// The bytes of one checkpoint section (docs/checkpoint-format.md): numbers in the
// machine's (little-endian) layout, vectors as a u64 count then the elements, strings
// as a u64 length then the bytes. ByteReader checks every read against the section's
// end, so a damaged section is refused with its name instead of read past.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {

static_assert(std::endian::native == std::endian::little, "checkpoints are written little-endian");

/// A checkpoint that cannot be used (unreadable, corrupt, truncated, another format
/// version or another scenario); the message names the file and what is wrong.
class CheckpointError : public InputError {
 public:
  using InputError::InputError;
};

class ByteWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>, "put() takes numbers; write structs field by field");
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  /// A vector of numbers, or of records whose every byte is a field (no padding).
  template <class T>
  void put_vector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>, "put_vector() takes numbers or padding-free records");
    put(static_cast<std::uint64_t>(values.size()));
    if (!values.empty()) bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void put_string(std::string_view text) {
    put(static_cast<std::uint64_t>(text.size()));
    bytes_.append(text.data(), text.size());
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  /// `what` names the section and file for error messages ("section 'PART' of 'x.ckpt'").
  ByteReader(std::string_view bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

  template <class T>
  T get() {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  template <class T>
  void get(T& value) { value = get<T>(); }
  template <class T>
  void get_vector(std::vector<T>& values) {
    const auto count = get<std::uint64_t>();
    if (count > (bytes_.size() - position_) / (sizeof(T) == 0 ? 1 : sizeof(T)))
      throw CheckpointError(fmt::format("{} holds {} elements of {} bytes but has only {} bytes left", what_, count,
                                        sizeof(T), bytes_.size() - position_));
    values.resize(count);
    if (count > 0)  // an empty vector's data() may be null, which memcpy may not take
      std::memcpy(static_cast<void*>(values.data()), take(count * sizeof(T)), count * sizeof(T));
  }
  std::string get_string() {
    const auto length = get<std::uint64_t>();
    if (length > bytes_.size() - position_)
      throw CheckpointError(fmt::format("{} ends inside a string of {} bytes", what_, length));
    return std::string(take(length), length);
  }
  bool at_end() const { return position_ == bytes_.size(); }
  const std::string& what() const { return what_; }
  /// Throws CheckpointError naming the section: "<what>: <message>".
  [[noreturn]] void fail(const std::string& message) const { throw CheckpointError(fmt::format("{}: {}", what_, message)); }

 private:
  const char* take(std::size_t n) {
    if (n > bytes_.size() - position_)
      throw CheckpointError(fmt::format("{} ends early: {} more bytes needed at offset {} of {}", what_, n, position_,
                                        bytes_.size()));
    const char* at = bytes_.data() + position_;
    position_ += n;
    return at;
  }

  std::string_view bytes_;
  std::size_t position_ = 0;
  std::string what_;
};

}  // namespace regodem

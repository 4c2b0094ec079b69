// Plain data to bytes and back: the solve's checkpoints (solve_checkpoint.cpp) and what ranks send
// each other. Native byte order and layout: the bytes are read back by the same build only
// (checkpoints record the build that wrote them and refuse another). Both ends work in memory or
// through a stream in pieces of about 1 MiB, so that a state of gigabytes is never held twice.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "walkrad/core/file_hash.h"

namespace walkrad {

// Bytes that do not read back as what was written (cut short, too long, from something else).
class ByteFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A checksum of a stream (FNV-1a's step on 8-byte words: damage, not tampering), fed in pieces of
// any size.
class Checksum {
 public:
  void add(const void* data, size_t size);
  uint64_t value() const;

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;
  uint8_t tail_[8] = {};
  size_t tail_size_ = 0;
};

class ByteWriter {
 public:
  ByteWriter() = default;  // into bytes()
  // Through a buffer: sink gets the bytes in order, in pieces (flush() hands over the last).
  explicit ByteWriter(std::function<void(const uint8_t*, size_t)> sink) : sink_(std::move(sink)) {}

  void write(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    if (sink_ && bytes_.size() + size >= kPiece) {
      flush();
      if (size >= kPiece) return sink_(p, size);  // a large list goes straight through
    }
    bytes_.insert(bytes_.end(), p, p + size);
  }
  void flush() {
    if (sink_ && !bytes_.empty()) sink_(bytes_.data(), bytes_.size());
    if (sink_) bytes_.clear();
  }
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    write(&v, sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(uint64_t(v.size()));
    write(v.data(), v.size() * sizeof(T));
  }
  void put_string(const std::string& s) {
    put(uint64_t(s.size()));
    write(s.data(), s.size());
  }
  std::vector<uint8_t>& bytes() { return bytes_; }  // in memory (no sink)

  static constexpr size_t kPiece = size_t(1) << 20;

 private:
  std::vector<uint8_t> bytes_;
  std::function<void(const uint8_t*, size_t)> sink_;
};

// Throws ByteFormatError when the bytes end early.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  explicit ByteReader(const std::vector<uint8_t>& v) : ByteReader(v.data(), v.size()) {}
  // From a stream of `size` bytes: source(dst, n) fills dst with its next n bytes.
  ByteReader(std::function<void(uint8_t*, size_t)> source, uint64_t size) : source_(std::move(source)), size_(size_t(size)) {}

  void read(void* dst, size_t n) {
    if (n > remaining()) throw ByteFormatError("truncated");
    auto* out = static_cast<uint8_t*>(dst);
    if (!source_) {
      if (n) std::memcpy(out, data_ + at_, n);
      at_ += n;
      return;
    }
    const size_t buffered = std::min(n, buffer_.size() - from_);
    if (buffered) std::memcpy(out, buffer_.data() + from_, buffered);
    from_ += buffered, at_ += buffered, out += buffered, n -= buffered;
    if (n == 0) return;
    if (n >= ByteWriter::kPiece) {  // a large list comes straight in
      source_(out, n);
      at_ += n;
      return;
    }
    buffer_.resize(std::min(ByteWriter::kPiece, remaining()));
    source_(buffer_.data(), buffer_.size());
    from_ = 0;
    read(out, n);
  }
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    read(&v, sizeof(T));
    return v;
  }
  template <class T>
  void get_vector(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = get<uint64_t>();
    if (n > remaining() / sizeof(T)) throw ByteFormatError("truncated (a list runs past the end)");
    v.resize(size_t(n));
    read(v.data(), size_t(n) * sizeof(T));
  }
  std::string get_string() {
    const auto n = get<uint64_t>();
    if (n > remaining()) throw ByteFormatError("truncated (a string runs past the end)");
    std::string s(size_t(n), '\0');
    read(s.data(), s.size());
    return s;
  }
  size_t remaining() const { return size_ - at_; }
  bool done() const { return at_ == size_; }

 private:
  const uint8_t* data_ = nullptr;
  std::function<void(uint8_t*, size_t)> source_;
  std::vector<uint8_t> buffer_;
  size_t from_ = 0;  // next byte of buffer_
  size_t size_, at_ = 0;
};

inline void Checksum::add(const void* data, size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  while (size > 0 && tail_size_ > 0) {  // complete a word begun by the last piece
    tail_[tail_size_++] = *p++, --size;
    if (tail_size_ == 8) {
      uint64_t w;
      std::memcpy(&w, tail_, 8);
      h_ = (h_ ^ w) * 0x100000001b3ull;
      tail_size_ = 0;
    }
  }
  for (; size >= 8; p += 8, size -= 8) {
    uint64_t w;
    std::memcpy(&w, p, 8);
    h_ = (h_ ^ w) * 0x100000001b3ull;
  }
  for (; size > 0; --size) tail_[tail_size_++] = *p++;
}

inline uint64_t Checksum::value() const { return fnv1a(tail_, tail_size_, h_); }  // the last bytes one by one

}  // namespace walkrad

// Plain data to bytes and back, in memory: the solve's checkpoints (solve_checkpoint.h) and what ranks
// send each other. Native byte order and layout: the bytes are read back by the same build only
// (checkpoints record the build that wrote them and refuse another).
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace walkrad {

class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(uint64_t(v.size()));
    const auto* p = reinterpret_cast<const uint8_t*>(v.data());
    bytes_.insert(bytes_.end(), p, p + v.size() * sizeof(T));
  }
  void put_string(const std::string& s) {
    put(uint64_t(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

// Throws std::runtime_error("truncated ...") when the bytes end early.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  explicit ByteReader(const std::vector<uint8_t>& v) : ByteReader(v.data(), v.size()) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, take(sizeof(T)), sizeof(T));
    return v;
  }
  template <class T>
  void get_vector(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = get<uint64_t>();
    if (n > (size_ - at_) / sizeof(T)) throw std::runtime_error("truncated data (a list runs past the end)");
    v.resize(size_t(n));
    if (n) std::memcpy(v.data(), take(size_t(n) * sizeof(T)), size_t(n) * sizeof(T));
  }
  std::string get_string() {
    const auto n = get<uint64_t>();
    if (n > size_ - at_) throw std::runtime_error("truncated data (a string runs past the end)");
    const auto* p = reinterpret_cast<const char*>(take(size_t(n)));
    return std::string(p, p + n);
  }
  bool done() const { return at_ == size_; }
  size_t remaining() const { return size_ - at_; }

 private:
  const uint8_t* take(size_t n) {
    if (n > size_ - at_) throw std::runtime_error("truncated data");
    const uint8_t* p = data_ + at_;
    at_ += n;
    return p;
  }
  const uint8_t* data_;
  size_t size_, at_ = 0;
};

}  // namespace walkrad

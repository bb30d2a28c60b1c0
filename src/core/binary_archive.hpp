#pragma once
// Flat binary archive of a run's state (checkpoints): little-endian host values as they are in
// memory, so a value read back is the same bits. Sections carry four-letter tags and every length
// is checked against the bytes left, so a truncated or foreign file gives a clear error instead
// of an unbounded allocation or garbage.
#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace periadapt {

class ArchiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bytes put out in parts (a large payload written without a copy of it in memory).
using ArchiveSink = std::function<void(const char* data, std::size_t n)>;

// An archive read in order from elsewhere (a file too large to hold twice): bytes read or skipped.
class ArchiveStream {
 public:
  virtual ~ArchiveStream() = default;
  // Throws ArchiveError past the end.
  virtual void read(void* to, std::size_t n) = 0;
  virtual void skip(std::uint64_t n) = 0;
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v{};
    read(&v, sizeof v);
    return v;
  }
};

class ArchiveWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&v);
    buf_.append(p, sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(v.size());
    buf_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put(const std::string& s) {
    put<std::uint64_t>(s.size());
    buf_.append(s);
  }
  template <class T>
  void put(const std::optional<T>& v) {
    put<std::uint8_t>(v.has_value());
    if (v) put(*v);
  }
  template <class T, std::size_t N>
  void put(const std::array<std::vector<T>, N>& a) {
    for (const auto& v : a) put(v);
  }
  void tag(const char (&t)[5]) { buf_.append(t, 4); }
  const std::string& bytes() const { return buf_; }
  std::string take() { return std::move(buf_); }

 private:
  std::string buf_;
};

class ArchiveReader {
 public:
  ArchiveReader(const std::string& bytes, std::string name) : buf_(bytes), name_(std::move(name)) {}
  template <class T>
  void get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), "a value");
    std::memcpy(&v, buf_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
  }
  template <class T>
  void get(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::uint64_t n = length(sizeof(T));
    v.resize(n);
    if (n) std::memcpy(v.data(), buf_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
  }
  void get(std::string& s) {
    const std::uint64_t n = length(1);
    s.assign(buf_.data() + pos_, n);
    pos_ += n;
  }
  template <class T>
  void get(std::optional<T>& v) {
    std::uint8_t has = 0;
    get(has);
    if (has) {
      T x{};
      get(x);
      v = x;
    } else {
      v.reset();
    }
  }
  template <class T, std::size_t N>
  void get(std::array<std::vector<T>, N>& a) {
    for (auto& v : a) get(v);
  }
  template <class T>
  T get() {
    T v{};
    get(v);
    return v;
  }
  void tag(const char (&t)[5]) {
    need(4, std::string("section ") + t);
    if (std::memcmp(buf_.data() + pos_, t, 4) != 0)
      throw ArchiveError(name_ + ": section " + t + " expected at byte " + std::to_string(pos_) +
                         ", found '" + buf_.substr(pos_, 4) + "' (a file from another version?)");
    pos_ += 4;
  }
  bool at_end() const { return pos_ == buf_.size(); }
  std::size_t position() const { return pos_; }

 private:
  void need(std::size_t n, const std::string& what) const {
    if (buf_.size() - pos_ < n)
      throw ArchiveError(name_ + ": ends inside " + what + " at byte " + std::to_string(pos_) +
                         " (truncated?)");
  }
  std::uint64_t length(std::size_t elem) {
    std::uint64_t n = 0;
    get(n);
    if (n > (buf_.size() - pos_) / elem)
      throw ArchiveError(name_ + ": an array of " + std::to_string(n) + " elements at byte " +
                         std::to_string(pos_) + " runs past the end (corrupt or truncated)");
    return n;
  }
  const std::string& buf_;
  std::string name_;
  std::size_t pos_ = 0;
};

}  // namespace periadapt

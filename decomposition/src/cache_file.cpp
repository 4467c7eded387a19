// Content hashes, checksums and atomic file writes of the on-disk caches (cache_file.h).

#include "deepcheck/decomposition/cache_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <sstream>
#include <system_error>
#include <thread>

namespace deepcheck::decomposition {

namespace fs = std::filesystem;

std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  return h;
}

void ContentHasher::bytes(const void* data, std::size_t size) {
  a_ = fnv1a(data, size, a_);
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    word_ |= static_cast<std::uint64_t>(p[i]) << (8 * filled_);
    if (++filled_ == 8) flush();
  }
}

void ContentHasher::u64(std::uint64_t x) {
  unsigned char b[8];
  for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(x >> (8 * i));
  bytes(b, 8);
}

void ContentHasher::f64(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  u64(bits);
}

std::string ContentHasher::hex() {
  if (filled_ > 0) flush();
  char out[33];
  std::snprintf(out, sizeof out, "%016llx%016llx", static_cast<unsigned long long>(a_),
                static_cast<unsigned long long>(b_));
  return out;
}

void ContentHasher::flush() {
  std::uint64_t z = b_ ^ (word_ + 0x9e3779b97f4a7c15ULL + (b_ << 6) + (b_ >> 2));
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  b_ = z ^ (z >> 31);
  word_ = 0;
  filled_ = 0;
}

bool cacheKeyBytes(const std::string& key, unsigned char out[16]) {
  if (key.size() != 32) return false;
  for (int i = 0; i < 16; ++i) {
    unsigned value = 0;
    for (int k = 0; k < 2; ++k) {
      const char c = key[2 * i + k];
      value <<= 4;
      if (c >= '0' && c <= '9') value |= static_cast<unsigned>(c - '0');
      else if (c >= 'a' && c <= 'f') value |= static_cast<unsigned>(c - 'a' + 10);
      else return false;
    }
    out[i] = static_cast<unsigned char>(value);
  }
  return true;
}

std::string systemReason(int error) { return std::error_code(error, std::generic_category()).message(); }

std::string readWholeFile(const std::string& path, std::string& data) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return systemReason(errno);
  data.clear();
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      ::close(fd);
      return systemReason(error);
    }
    data.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return "";
}

namespace {

/// Writes `data` to `path`, which must not exist yet; "" on success, else the system's reason
/// (a full disk shows at write or close).
std::string writeNewFile(const std::string& path, const std::string& data) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return systemReason(errno);
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      ::close(fd);
      return systemReason(error);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) return systemReason(errno);
  return "";
}

}  // namespace

std::string writeFileAtomically(const std::string& directory, const std::string& path, const std::string& data) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) return "cannot create " + directory + ": " + ec.message();
  // A name no other process or thread uses, in the same directory (rename is atomic there).
  static std::atomic<unsigned> counter{0};
  std::ostringstream temp;
  temp << path << ".tmp." << ::getpid() << '.' << std::hash<std::thread::id>{}(std::this_thread::get_id()) << '.'
       << counter++;
  if (const std::string why = writeNewFile(temp.str(), data); !why.empty()) {
    fs::remove(temp.str(), ec);
    return "cannot write " + temp.str() + ": " + why;
  }
  fs::rename(temp.str(), path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp.str(), ignored);
    return "cannot rename " + temp.str() + " to " + path + ": " + ec.message();
  }
  return "";
}

}  // namespace deepcheck::decomposition

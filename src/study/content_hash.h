// A 128-bit content hash for cache keys: two independently seeded 64-bit
// lanes over the bytes fed in. Not cryptographic — it names cache entries, it
// does not defend against anyone.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace pathlab {

class ContentHash {
  public:
    void bytes(const void* data, size_t size);
    void text(const std::string& s);  // length-prefixed, so "ab","c" ≠ "a","bc"
    void integer(uint64_t v);
    void real(double v);
    void file(const std::filesystem::path& path);  // throws InputError when unreadable
    std::string hex() const;                       // 32 hexadecimal digits

  private:
    void word(uint64_t w);
    uint64_t a_ = 0x243f6a8885a308d3ULL, b_ = 0x13198a2e03707344ULL;
    uint64_t count_ = 0;
};

}  // namespace pathlab

#include "study/content_hash.h"

#include <cstring>
#include <fstream>

#include "core/error.h"
#include "core/hash.h"

namespace pathlab {

void ContentHash::word(uint64_t w) {
    a_ = mixBits(a_ ^ (w + 0x9e3779b97f4a7c15ULL)) + count_;
    b_ = mixBits(b_ + (w ^ 0xc2b2ae3d27d4eb4fULL)) ^ (count_ << 1);
    ++count_;
}

void ContentHash::bytes(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        uint64_t w;
        std::memcpy(&w, p + i, 8);
        word(w);
    }
    uint64_t tail = 0;
    if (size > i) std::memcpy(&tail, p + i, size - i);
    word(tail ^ (uint64_t(size - i) << 56));
}

void ContentHash::text(const std::string& s) {
    integer(s.size());
    bytes(s.data(), s.size());
}

void ContentHash::integer(uint64_t v) {
    word(v);
}

void ContentHash::real(double v) {
    uint64_t w;
    std::memcpy(&w, &v, 8);
    word(w);
}

void ContentHash::file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot read '" + path.string() + "' to hash it");
    std::vector<char> buffer(1 << 20);
    uint64_t total = 0;
    while (in) {
        in.read(buffer.data(), std::streamsize(buffer.size()));
        const auto n = size_t(in.gcount());
        bytes(buffer.data(), n);
        total += n;
    }
    integer(total);
}

std::string ContentHash::hex() const {
    static const char* digits = "0123456789abcdef";
    std::string out;
    for (uint64_t lane : {mixBits(a_ ^ count_), mixBits(b_ + count_)})
        for (int shift = 60; shift >= 0; shift -= 4) out += digits[(lane >> shift) & 15];
    return out;
}

}  // namespace pathlab

// The PLY reader's input side (used by ply_mesh.cpp only): the file streamed
// through a fixed buffer, and the decoding of one value at a time from it in
// ASCII or binary of either byte order. Streaming keeps the reader's memory to
// the mesh it builds plus 1 MiB, and spares the page faults of a file-sized
// buffer, which cost more than the parsing (a 29 MB file: about 7000 faults).
#pragma once

#include <zlib.h>

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

namespace pathlab::pbrt::ply {

enum class Type : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

// PLY's type names, old (char … double) and new (int8 … float64).
inline bool parseType(std::string_view s, Type& t) {
    constexpr std::string_view names[8][2] = {
        {"char", "int8"}, {"uchar", "uint8"}, {"short", "int16"},   {"ushort", "uint16"},
        {"int", "int32"}, {"uint", "uint32"}, {"float", "float32"}, {"double", "float64"}};
    for (int i = 0; i < 8; ++i)
        if (s == names[i][0] || s == names[i][1]) {
            t = Type(i);
            return true;
        }
    return false;
}

inline size_t typeSize(Type t) {
    constexpr size_t sizes[8] = {1, 1, 2, 2, 4, 4, 4, 8};
    return sizes[int(t)];
}

inline bool isInteger(Type t) {
    return t != Type::Float32 && t != Type::Float64;
}

// Thrown where the file ends too early, a value is not a number, or reading
// fails; the reader turns them into an InputError saying where.
struct Truncated {};
struct NotANumber {
    std::string token;
};
struct ReadError {};

class Source {
  public:
    static constexpr size_t kBufferSize = size_t(1) << 20;

    // zlib reads gzip-compressed files (pbrt-v4 scenes ship .ply.gz) and,
    // transparently, uncompressed ones.
    explicit Source(gzFile file) : file_(file), buffer_(new char[kBufferSize]) {}

    const char* data() const { return buffer_.get() + pos_; }
    size_t available() const { return end_ - pos_; }
    void consume(size_t n) { pos_ += n; }
    // Bytes consumed since the start of the file.
    uint64_t offset() const { return dropped_ + pos_; }

    // Makes at least n (≤ kBufferSize) bytes available, unless the file ends
    // first; returns how many are.
    size_t fill(size_t n) {
        if (available() >= n) return available();
        std::memmove(buffer_.get(), data(), available());
        dropped_ += pos_;
        end_ = available();
        pos_ = 0;
        while (end_ < n) {
            const int got = gzread(file_, buffer_.get() + end_, unsigned(kBufferSize - end_));
            if (got < 0) throw ReadError{};
            if (got == 0) {
                int error = Z_OK;
                gzerror(file_, &error);
                if (error != Z_OK && error != Z_BUF_ERROR) throw ReadError{};
                break;  // the end (a gzip stream cut short ends early too)
            }
            end_ += size_t(got);
        }
        return end_;
    }

  private:
    gzFile file_;
    std::unique_ptr<char[]> buffer_;  // not a vector: no zeroing of 1 MiB per file
    size_t pos_ = 0, end_ = 0;
    uint64_t dropped_ = 0;  // bytes before the buffer's start
};

template <bool Swap>
class BinaryInput {
  public:
    explicit BinaryInput(Source& source) : in_(source) {}
    double real(Type t) {
        switch (t) {
            case Type::Int8:
                return load<int8_t>();
            case Type::UInt8:
                return load<uint8_t>();
            case Type::Int16:
                return load<int16_t>();
            case Type::UInt16:
                return load<uint16_t>();
            case Type::Int32:
                return load<int32_t>();
            case Type::UInt32:
                return load<uint32_t>();
            case Type::Float32:
                return load<float>();
            case Type::Float64:
                return load<double>();
        }
        return 0;
    }
    // Integer types only (the header checks that lists and indices have one).
    int64_t integer(Type t) { return int64_t(real(t)); }
    void skip(Type t) {
        const size_t n = typeSize(t);
        if (in_.available() < n && in_.fill(n) < n) throw Truncated{};
        in_.consume(n);
    }

  private:
    template <typename T>
    T load() {
        using U = std::conditional_t<
            sizeof(T) == 1, uint8_t,
            std::conditional_t<sizeof(T) == 2, uint16_t,
                               std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>>;
        if (in_.available() < sizeof(U) && in_.fill(sizeof(U)) < sizeof(U)) throw Truncated{};
        U u;
        std::memcpy(&u, in_.data(), sizeof u);
        in_.consume(sizeof u);
        if constexpr (Swap && sizeof(U) == 2) u = __builtin_bswap16(u);
        if constexpr (Swap && sizeof(U) == 4) u = __builtin_bswap32(u);
        if constexpr (Swap && sizeof(U) == 8) u = __builtin_bswap64(u);
        return std::bit_cast<T>(u);
    }
    Source& in_;
};

// ASCII: whitespace-separated numbers; line breaks carry no meaning (as in
// rply, the reader pbrt-v4 uses).
class AsciiInput {
  public:
    explicit AsciiInput(Source& source) : in_(source) {}
    double real(Type t) {
        if (isInteger(t)) return double(integer(t));
        return number<double>();
    }
    int64_t integer(Type) { return number<int64_t>(); }
    void skip(Type t) { real(t); }

  private:
    static constexpr size_t kLongest = 256;  // longer than any number written out
    static bool space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

    template <typename T>
    T number() {
        const std::string_view tok = token();
        // from_chars takes no leading '+', which some writers emit.
        const char* first = tok.data() + (tok.size() > 1 && tok[0] == '+' ? 1 : 0);
        T v = 0;
        const auto [end, ec] = std::from_chars(first, tok.data() + tok.size(), v);
        if (ec != std::errc() || end != tok.data() + tok.size())
            throw NotANumber{std::string(tok.substr(0, 40))};
        in_.consume(tok.size());
        return v;
    }

    // The next token, at the front of the buffer's available bytes (valid
    // until the next read).
    std::string_view token() {
        for (;;) {
            while (in_.available() > 0 && space(*in_.data())) in_.consume(1);
            if (in_.available() > 0) break;
            if (in_.fill(1) == 0) throw Truncated{};
        }
        size_t n = 0;
        for (;;) {
            const char* d = in_.data();
            const size_t avail = in_.available();
            while (n < avail && !space(d[n])) ++n;
            // A token ends before the buffer does or at the end of the file.
            if (n < avail || in_.fill(n + 1) <= n) break;
            if (n >= kLongest) throw NotANumber{std::string(in_.data(), 40) + "..."};
        }
        return {in_.data(), n};
    }
    Source& in_;
};

}  // namespace pathlab::pbrt::ply

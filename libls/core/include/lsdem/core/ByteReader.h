/// @file ByteReader.h
/// @brief Reads what a ByteWriter wrote, in the same order, from bytes in memory. Every read
///        is bounded: bytes that end early, and counts larger than what is left could hold,
///        throw DamagedBytes before anything is allocated, so damaged input (a truncated file,
///        a fuzzer's bytes) cannot read out of bounds or ask for terabytes. The caller turns
///        DamagedBytes into its own message (a checkpoint's names the file).
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace lsdem {

/// The bytes end before what is read from them, or hold a count that cannot be right.
class DamagedBytes : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

class ByteReader
{
public:
    ByteReader(const char* begin, const char* end) : mAt(begin), mEnd(end) {}
    explicit ByteReader(const std::string& bytes) : ByteReader(bytes.data(), bytes.data() + bytes.size()) {}
    explicit ByteReader(const std::vector<char>& bytes)
        : ByteReader(bytes.data(), bytes.data() + bytes.size())
    {
    }

    template <class T> T value()
    {
        static_assert(std::is_trivially_copyable_v<T>, "only plain values are read as bytes");
        T v{};
        take(&v, sizeof v);
        return v;
    }
    /// @a n values into @a first (written by ByteWriter::values).
    template <class T> void values(T* first, size_t n)
    {
        static_assert(std::is_trivially_copyable_v<T>, "only plain values are read as bytes");
        if (n > left() / sizeof(T)) damaged("a run of values");
        take(first, n * sizeof(T));
    }
    /// A count of items stored in at least @a itemBytes each (≥ 1): never more than the rest of
    /// the bytes can hold.
    uint64_t count(uint64_t itemBytes = 1)
    {
        const auto n = value<uint64_t>();
        if (n > left() / (itemBytes == 0 ? 1 : itemBytes)) damaged("a count");
        return n;
    }
    double number() { return value<double>(); }
    int64_t integer() { return value<int64_t>(); }
    std::string text()
    {
        std::string s(count(1), '\0');
        take(s.data(), s.size());
        return s;
    }
    template <class T> std::vector<T> list()
    {
        std::vector<T> v(count(sizeof(T)));
        values(v.data(), v.size());
        return v;
    }
    std::vector<double> numbers() { return list<double>(); }
    /// Whether the next bytes are @a n bytes equal to @a bytes; consumed if they are.
    bool skipIfNext(const void* bytes, size_t n)
    {
        if (left() < n || std::memcmp(mAt, bytes, n) != 0) return false;
        mAt += n;
        return true;
    }
    size_t left() const { return static_cast<size_t>(mEnd - mAt); }
    bool atEnd() const { return mAt == mEnd; }

    /// Throws DamagedBytes: @a what (a count, a name) did not fit or made no sense.
    [[noreturn]] static void damaged(const std::string& what)
    {
        throw DamagedBytes("the bytes end early or are damaged (reading " + what + ")");
    }

private:
    void take(void* to, size_t n)
    {
        if (n > left()) damaged(std::to_string(n) + " bytes with " + std::to_string(left()) + " left");
        if (n > 0) std::memcpy(to, mAt, n);
        mAt += n;
    }

    const char* mAt;
    const char* mEnd;
};

} // namespace lsdem

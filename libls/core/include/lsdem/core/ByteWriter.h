/// @file ByteWriter.h
/// @brief lsdem's one binary writer: plain values, counts, strings and lists appended to a
///        byte buffer in the order given, numbers as their bytes (bit for bit), in the
///        machine's byte order. ByteReader.h reads them back in the same order. The formats
///        built on it: checkpoints (a file, versioned by its own header), the grains and
///        histories ranks exchange, and study records sent between MPI ranks.
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace lsdem {

/// Appends to @a Buffer, a contiguous container of char (std::string or std::vector<char>):
/// one given to it, or its own (bytes()). Counts (of a string's characters or a list's items)
/// are always 64-bit, so a layout does not depend on the platform's size_t.
template <class Buffer = std::string>
class ByteWriter
{
public:
    /// Writes into a buffer of its own.
    ByteWriter() : mOut(&mOwn) {}
    /// Appends to @a out, which must outlive the writer.
    explicit ByteWriter(Buffer& out) : mOut(&out) {}
    ByteWriter(ByteWriter&& other) noexcept
        : mOwn(std::move(other.mOwn)), mOut(other.mOut == &other.mOwn ? &mOwn : other.mOut)
    {
    }
    ByteWriter(const ByteWriter&) = delete;
    ByteWriter& operator=(const ByteWriter&) = delete;
    ByteWriter& operator=(ByteWriter&&) = delete;

    /// What has been written (all of the buffer, if it was given with bytes in it).
    const Buffer& bytes() const { return *mOut; }

    /// A value of a trivially copyable type, as its bytes.
    template <class T> ByteWriter& value(const T& v)
    {
        static_assert(std::is_trivially_copyable_v<T>, "only plain values are written as bytes");
        return raw(&v, sizeof v);
    }
    /// @a n values from @a first, with no count before them (the reader knows how many).
    template <class T> ByteWriter& values(const T* first, size_t n)
    {
        static_assert(std::is_trivially_copyable_v<T>, "only plain values are written as bytes");
        return raw(first, n * sizeof(T));
    }
    ByteWriter& count(uint64_t n) { return value(n); }
    ByteWriter& number(double v) { return value(v); }
    ByteWriter& integer(int64_t v) { return value(v); }
    /// The string's length, then its characters.
    ByteWriter& text(const std::string& s)
    {
        count(s.size());
        return raw(s.data(), s.size());
    }
    /// The list's length, then its items.
    template <class T> ByteWriter& list(const std::vector<T>& v)
    {
        count(v.size());
        return values(v.data(), v.size());
    }
    ByteWriter& numbers(const std::vector<double>& v) { return list(v); }
    /// Bytes as they are (a file's magic word, a record written elsewhere).
    ByteWriter& raw(const void* bytes, size_t n)
    {
        const auto* first = static_cast<const char*>(bytes);
        mOut->insert(mOut->end(), first, first + n);
        return *this;
    }

private:
    Buffer mOwn;
    Buffer* mOut;
};

} // namespace lsdem

/// @file RecordBytes.h
/// @brief A study run's description or result as bytes, to send it from one MPI rank to
///        another: numbers (bit for bit, so a result is the same wherever it was computed) and
///        strings, written in order and read back in the same order. No MPI here.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace lsdem {

class RecordWriter
{
public:
    RecordWriter& number(double v) { return raw(&v, sizeof v); }
    RecordWriter& integer(long long v)
    {
        const std::int64_t fixed = v;  // the same width on every rank
        return raw(&fixed, sizeof fixed);
    }
    RecordWriter& text(const std::string& s)
    {
        integer(static_cast<long long>(s.size()));
        mBytes.append(s);
        return *this;
    }
    RecordWriter& numbers(const std::vector<double>& v)
    {
        integer(static_cast<long long>(v.size()));
        return v.empty() ? *this : raw(v.data(), v.size() * sizeof(double));
    }
    const std::string& bytes() const { return mBytes; }

private:
    RecordWriter& raw(const void* p, size_t n)
    {
        mBytes.append(static_cast<const char*>(p), n);
        return *this;
    }
    std::string mBytes;
};

/// Reads what a RecordWriter wrote, in the same order. Reading past the end, or a length that
/// does not fit, is a program error (std::logic_error): the two sides disagree on the layout.
class RecordReader
{
public:
    explicit RecordReader(const std::string& bytes) : mBytes(bytes) {}
    double number()
    {
        double v;
        raw(&v, sizeof v);
        return v;
    }
    long long integer()
    {
        std::int64_t v;
        raw(&v, sizeof v);
        return v;
    }
    std::string text()
    {
        const size_t n = length(1);
        std::string s = mBytes.substr(mPosition, n);
        mPosition += n;
        return s;
    }
    std::vector<double> numbers()
    {
        std::vector<double> v(length(sizeof(double)));
        if (!v.empty()) raw(v.data(), v.size() * sizeof(double));
        return v;
    }
    bool atEnd() const { return mPosition == mBytes.size(); }

private:
    size_t length(size_t itemSize)
    {
        const long long n = integer();
        if (n < 0 || static_cast<unsigned long long>(n) > (mBytes.size() - mPosition) / itemSize)
            throw std::logic_error("run record: a length of " + std::to_string(n) +
                                   " items runs past the end of the record");
        return static_cast<size_t>(n);
    }
    void raw(void* p, size_t n)
    {
        if (n > mBytes.size() - mPosition)
            throw std::logic_error("run record: read past the end of the record");
        std::memcpy(p, mBytes.data() + mPosition, n);
        mPosition += n;
    }
    const std::string& mBytes;
    size_t mPosition = 0;
};

} // namespace lsdem

// Grains, their states and their contact histories as bytes, for GhostDecomposition (private
// to the simulation library). Numbers travel as their bytes, so a receiver's copy is bit for
// bit the sender's.
#pragma once

#include "lsdem/simulation/World.h"

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace lsdem::grainpacking {

/// Appends plain values and strings to a byte buffer.
class Writer
{
public:
    explicit Writer(std::vector<char>& out) : mOut(out) {}

    template <class T> void put(const T& value)
    {
        const size_t at = mOut.size();
        mOut.resize(at + sizeof(T));
        std::memcpy(mOut.data() + at, &value, sizeof(T));
    }
    void putDoubles(const double* values, size_t count)
    {
        const size_t at = mOut.size();
        mOut.resize(at + count * sizeof(double));
        std::memcpy(mOut.data() + at, values, count * sizeof(double));
    }
    void putString(const std::string& s)
    {
        put(static_cast<unsigned>(s.size()));
        mOut.insert(mOut.end(), s.begin(), s.end());
    }

private:
    std::vector<char>& mOut;
};

/// Reads what a Writer wrote; @throw std::runtime_error if the bytes end early (a bug).
class Reader
{
public:
    Reader(const char* at, const char* end) : mAt(at), mEnd(end) {}

    bool done() const { return mAt == mEnd; }
    template <class T> T get()
    {
        need(sizeof(T));
        T value;
        std::memcpy(&value, mAt, sizeof(T));
        mAt += sizeof(T);
        return value;
    }
    void getDoubles(double* values, size_t count)
    {
        need(count * sizeof(double));
        std::memcpy(values, mAt, count * sizeof(double));
        mAt += count * sizeof(double);
    }
    std::string getString()
    {
        const size_t n = get<unsigned>();
        need(n);
        std::string s(mAt, n);
        mAt += n;
        return s;
    }

private:
    void need(size_t bytes) const
    {
        if (size_t(mEnd - mAt) < bytes)
            throw std::runtime_error("grain packing: the bytes end early");
    }

    const char* mAt;
    const char* mEnd;
};

/// Everything of a grain (its asset by index into World::assets).
void putGrain(Writer& out, const Grain& g, int assetIndex);
Grain getGrain(Reader& in, const World& world);

/// What a ghost needs each step: pose, velocity and angular momentum.
void putState(Writer& out, const Grain& g);
void getState(Reader& in, Grain& g);

void putHistory(Writer& out, const ShearHistory& h);
void getHistory(Reader& in, ShearHistory& h, std::vector<ShearHistory::Entry>& buffer);

} // namespace lsdem::grainpacking

#include "SlotResults.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace lsdem::slotresults {

namespace {

// Signed integers as zigzag varints: 7 bits a byte, low first, high bit = more to come.
void putInteger(std::vector<char>& out, long long value)
{
    uint64_t v = (uint64_t(value) << 1) ^ uint64_t(value >> 63);
    while (v >= 0x80) {
        out.push_back(static_cast<char>((v & 0x7f) | 0x80));
        v >>= 7;
    }
    out.push_back(static_cast<char>(v));
}

void putDoubles(std::vector<char>& out, const double* values, size_t count)
{
    const size_t at = out.size();
    out.resize(at + count * sizeof(double));
    std::memcpy(out.data() + at, values, count * sizeof(double));
}

void putHistory(std::vector<char>& out, const ShearHistory& h)
{
    putInteger(out, static_cast<long long>(h.size()));
    for (const ShearHistory::Entry& e : h.entries()) {
        putInteger(out, e.node);
        putDoubles(out, e.force.data(), 3);
    }
}

class Reader
{
public:
    Reader(const char*& at, const char* end) : mAt(at), mEnd(end) {}

    long long integer()
    {
        uint64_t v = 0;
        for (int shift = 0;; shift += 7) {
            need(1);
            const auto byte = static_cast<unsigned char>(*mAt++);
            v |= uint64_t(byte & 0x7f) << shift;
            if (!(byte & 0x80)) break;
            if (shift > 56) throw std::runtime_error("slot results: malformed integer");
        }
        return static_cast<long long>((v >> 1) ^ (~(v & 1) + 1));
    }

    void doubles(double* values, size_t count)
    {
        need(count * sizeof(double));
        std::memcpy(values, mAt, count * sizeof(double));
        mAt += count * sizeof(double);
    }

    void history(ShearHistory& h, std::vector<ShearHistory::Entry>& buffer)
    {
        buffer.resize(size_t(integer()));
        for (ShearHistory::Entry& e : buffer) {
            e.node = static_cast<int>(integer());
            doubles(e.force.data(), 3);
        }
        h.replaceWith(buffer);
    }

private:
    void need(size_t bytes) const
    {
        if (size_t(mEnd - mAt) < bytes)
            throw std::runtime_error("slot results: the bytes of a slot end early");
    }

    const char*& mAt;
    const char* mEnd;
};

} // namespace

bool isEmpty(const PairForces& r)
{
    if (r.contactNodes != 0 || r.pointForcesOnFirst != 0) return false;
    static const double zeros[9] = {};
    const auto zero = [](const double* p, size_t n) {
        return std::memcmp(p, zeros, n * sizeof(double)) == 0;
    };
    return zero(r.forceOnFirst.data(), 3) && zero(r.torqueOnFirst.data(), 3) &&
           zero(r.forceOnSecond.data(), 3) && zero(r.torqueOnSecond.data(), 3) &&
           zero(&r.elasticEnergy, 1) && zero(r.normalStiffness.data(), 9);
}

void pack(const ContactSlot& s, bool withForces, std::vector<char>& out)
{
    putInteger(out, s.stats.nodesConsidered);
    putInteger(out, s.stats.nodesCulled);
    putInteger(out, s.stats.nodesSampled);
    putInteger(out, s.stats.nodesInContact);
    const PairForces& r = s.result;
    const bool empty = isEmpty(r);
    out.push_back(empty ? 0 : 1);
    if (!empty) {
        putDoubles(out, r.forceOnFirst.data(), 3);
        putDoubles(out, r.torqueOnFirst.data(), 3);
        putDoubles(out, r.forceOnSecond.data(), 3);
        putDoubles(out, r.torqueOnSecond.data(), 3);
        putDoubles(out, &r.elasticEnergy, 1);
        putDoubles(out, r.normalStiffness.data(), 9);
        putInteger(out, r.contactNodes);
        putInteger(out, r.pointForcesOnFirst);
    }
    if (s.boundary < 0) {
        putHistory(out, s.pairHistory->shearOnFirstNodes);
        putHistory(out, s.pairHistory->shearOnSecondNodes);
    } else {
        putHistory(out, *s.boundaryHistory);
    }
    if (withForces) {
        putInteger(out, static_cast<long long>(s.forces.size()));
        for (const PointForce& f : s.forces) {
            putInteger(out, f.node);
            putDoubles(out, f.force.data(), 3);
            putDoubles(out, f.point.data(), 3);
            putDoubles(out, &f.stiffness, 1);
        }
    }
}

void unpack(const char*& at, const char* end, bool withForces, ContactSlot& s,
            std::vector<ShearHistory::Entry>& buffer)
{
    Reader in(at, end);
    s.stats.nodesConsidered = in.integer();
    s.stats.nodesCulled = in.integer();
    s.stats.nodesSampled = in.integer();
    s.stats.nodesInContact = in.integer();
    PairForces& r = s.result;
    r = PairForces();
    if (at == end) throw std::runtime_error("slot results: the bytes of a slot end early");
    if (*at++ != 0) {
        in.doubles(r.forceOnFirst.data(), 3);
        in.doubles(r.torqueOnFirst.data(), 3);
        in.doubles(r.forceOnSecond.data(), 3);
        in.doubles(r.torqueOnSecond.data(), 3);
        in.doubles(&r.elasticEnergy, 1);
        in.doubles(r.normalStiffness.data(), 9);
        r.contactNodes = static_cast<int>(in.integer());
        r.pointForcesOnFirst = static_cast<int>(in.integer());
    }
    if (s.boundary < 0) {
        in.history(s.pairHistory->shearOnFirstNodes, buffer);
        in.history(s.pairHistory->shearOnSecondNodes, buffer);
    } else {
        in.history(*s.boundaryHistory, buffer);
    }
    s.forces.clear();
    if (withForces) {
        s.forces.resize(size_t(in.integer()));
        for (PointForce& f : s.forces) {
            f.node = static_cast<int>(in.integer());
            in.doubles(f.force.data(), 3);
            in.doubles(f.point.data(), 3);
            in.doubles(&f.stiffness, 1);
        }
    }
}

} // namespace lsdem::slotresults

// A checkpoint's bytes (private to the run library): lsdem's binary writer with the vectors,
// rotations and shear histories a checkpoint holds, and the reader that gives them back and
// turns anything short, out of range or out of order into an Error naming the file
// (Checkpoint.cpp writes and reads the layout).
#pragma once

#include "lsdem/contact/ShearHistory.h"
#include "lsdem/core/Vec3.h"
#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"
#include "lsdem/core/Error.h"

#include <cmath>
#include <cstdint>
#include <string>

namespace lsdem::checkpointbytes {

using Writer = ByteWriter<std::string>;

inline bool allFinite(const Vec3& v)
{
    return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

inline void putVec(Writer& w, const Vec3& v)
{
    w.values(v.data(), 3);
}

inline void putQuat(Writer& w, const Quat& q)
{
    w.number(q.w()).number(q.x()).number(q.y()).number(q.z());
}

/// Shear entries as (node, force), in the history's (sorted) order.
inline void putShear(Writer& w, const ShearHistory& h)
{
    w.count(h.size());
    for (const ShearHistory::Entry& e : h.entries())
        w.value<int32_t>(e.node), putVec(w, e.force), w.value<double>(e.stiffness);
}

/// Reads a checkpoint's bytes in memory, in the order saveCheckpoint wrote them. Anything short,
/// out of range or out of order is an Error naming the file: ByteReader's DamagedBytes, and
/// fail() for what only the checkpoint knows to be wrong.
class Reader : public ByteReader
{
public:
    Reader(const std::string& bytes, std::string path) : ByteReader(bytes), mPath(std::move(path)) {}

    Vec3 vec()
    {
        Vec3 v;
        values(v.data(), 3);
        return v;
    }
    Quat quat()
    {
        const double w = number(), x = number(), y = number(), z = number();
        return Quat(w, x, y, z);
    }
    /// A shear history; with each spring's stiffness from version 10 on (0, not known, before).
    ShearHistory shear(bool withStiffness)
    {
        ShearHistory h;
        const uint64_t n =
            count(sizeof(int32_t) + (withStiffness ? 4 : 3) * sizeof(double));
        for (uint64_t k = 0; k < n; ++k) {
            const int node = value<int32_t>();
            const Vec3 force = vec();
            const double stiffness = withStiffness ? number() : 0.0;
            if (!h.empty() && node <= h.entries().back().node) fail();  // written sorted
            if (!allFinite(force) || !(std::isfinite(stiffness) && stiffness >= 0.0)) fail();
            h.append(node, force, stiffness);
        }
        return h;
    }
    /// Whether the bytes go on with @a magic (8 bytes); consumed if they do.
    bool magic(const char (&magic)[8]) { return skipIfNext(magic, sizeof magic); }
    [[noreturn]] void fail() const
    {
        throw Error(mPath, "the checkpoint is truncated or corrupt",
                    "use an earlier checkpoint or start the run again");
    }

private:
    std::string mPath;
};

} // namespace lsdem::checkpointbytes

#include "lsdem/run/Checkpoint.h"

#include "WorldFingerprint.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

namespace lsdem {

namespace {

const char kMagic[8] = {'L', 'S', 'D', 'E', 'M', 'C', 'K', 'P'};
/// 2: each boundary also keeps its contact stiffness and dashpot (a servo wall's gain).
/// 3: the fingerprint of the world's grains and their assets (WorldFingerprint.h) follows the
///    record.
/// 4: the run's end condition follows the fingerprint (a flag, then the end if set).
/// 5: the assets' fingerprints take the level set's slope bound where φ ≥ 0
///    (levelSetSlopeBound since 2026-11-27); those of a version 3 or 4 file took the earlier
///    bound over the whole grid, so its assets are not compared (its grains still are).
const uint32_t kVersion = 5;
const uint32_t kOldestVersion = 1;

/// Raw little-endian-as-the-machine binary writer; doubles are copied bit for bit.
class Writer
{
public:
    explicit Writer(std::ostream& out) : mOut(out) {}
    template <typename T> void pod(const T& v) { mOut.write(reinterpret_cast<const char*>(&v), sizeof v); }
    void text(const std::string& s)
    {
        pod<uint64_t>(s.size());
        mOut.write(s.data(), static_cast<std::streamsize>(s.size()));
    }
    void vec(const Vec3& v) { pod(v.x()), pod(v.y()), pod(v.z()); }
    void quat(const Quat& q) { pod(q.w()), pod(q.x()), pod(q.y()), pod(q.z()); }
    void doubles(const std::vector<double>& v)
    {
        pod<uint64_t>(v.size());
        for (double d : v) pod(d);
    }
    void words(const std::vector<uint64_t>& v)
    {
        pod<uint64_t>(v.size());
        for (uint64_t x : v) pod(x);
    }
    void shear(const ShearHistory& h)
    {
        pod<uint64_t>(h.size());
        for (const ShearHistory::Entry& e : h.entries()) pod<int32_t>(e.node), vec(e.force);
    }

private:
    std::ostream& mOut;
};

/// Reads a checkpoint's bytes in memory, in the order Writer wrote them; anything short or out
/// of range is an Error naming the file.
class Reader
{
public:
    Reader(const std::string& bytes, std::string path) : mBytes(bytes), mPath(std::move(path)) {}
    template <typename T> T pod()
    {
        T v{};
        take(&v, sizeof v);
        return v;
    }
    /// A count of items stored in at least @a itemBytes each. A damaged count could ask for
    /// terabytes (std::bad_alloc instead of an Error): it may not exceed what the rest of the
    /// file can hold, checked before anything is allocated for it.
    uint64_t count(uint64_t itemBytes)
    {
        const uint64_t n = pod<uint64_t>();
        if (n > left() / itemBytes) fail();
        return n;
    }
    std::string text()
    {
        std::string s(count(1), '\0');
        take(s.data(), s.size());
        return s;
    }
    Vec3 vec()
    {
        Vec3 v;
        for (int k = 0; k < 3; ++k) v[k] = pod<double>();
        return v;
    }
    Quat quat()
    {
        const double w = pod<double>(), x = pod<double>(), y = pod<double>(), z = pod<double>();
        return Quat(w, x, y, z);
    }
    std::vector<double> doubles()
    {
        std::vector<double> v(count(sizeof(double)));
        for (double& d : v) d = pod<double>();
        return v;
    }
    ShearHistory shear()
    {
        ShearHistory h;
        const uint64_t n = count(sizeof(int32_t) + 3 * sizeof(double));
        for (uint64_t k = 0; k < n; ++k) {
            const int node = pod<int32_t>();
            const Vec3 force = vec();
            if (!h.empty() && node <= h.entries().back().node) fail();  // written sorted
            h.append(node, force);
        }
        return h;
    }
    std::vector<uint64_t> words()
    {
        std::vector<uint64_t> v(count(sizeof(uint64_t)));
        for (uint64_t& x : v) x = pod<uint64_t>();
        return v;
    }
    /// Whether the next bytes are the magic (consumed if they are).
    bool magic()
    {
        if (left() < sizeof kMagic || std::memcmp(mBytes.data() + mAt, kMagic, sizeof kMagic) != 0)
            return false;
        mAt += sizeof kMagic;
        return true;
    }
    [[noreturn]] void fail() const
    {
        throw Error(mPath, "the checkpoint is truncated or corrupt",
                    "use an earlier checkpoint or start the run again");
    }

private:
    uint64_t left() const { return mBytes.size() - mAt; }
    void take(void* to, size_t n)
    {
        if (n > left()) fail();
        std::memcpy(to, mBytes.data() + mAt, n);
        mAt += n;
    }

    const std::string& mBytes;
    std::string mPath;
    size_t mAt = 0;
};

void writeRecord(Writer& w, const RunRecord& r)
{
    w.pod<uint64_t>(r.energyRows.size());
    for (const auto& row : r.energyRows) w.doubles(row);
    w.pod<uint64_t>(r.boundaryRows.size());
    for (const auto& rows : r.boundaryRows) {
        w.pod<uint64_t>(rows.size());
        for (const auto& row : rows) w.doubles(row);
    }
    w.doubles(r.vtkFrameTimes);
}

RunRecord readRecord(Reader& r)
{
    RunRecord rec;
    const uint64_t rowBytes = sizeof(uint64_t);  // a row is at least its own count
    rec.energyRows.resize(r.count(rowBytes));
    for (auto& row : rec.energyRows) row = r.doubles();
    rec.boundaryRows.resize(r.count(rowBytes));
    for (auto& rows : rec.boundaryRows) {
        rows.resize(r.count(rowBytes));
        for (auto& row : rows) row = r.doubles();
    }
    rec.vtkFrameTimes = r.doubles();
    return rec;
}

/// The whole file at @a path (one reading: see Checkpoint::fileBytes).
std::string readFileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(path, "cannot open the checkpoint", "check the path (lsdem-run writes "
                                                        "<out>/checkpoint.lsdem)");
    std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad())
        throw Error(path, "cannot read the checkpoint", "check the file and its folder");
    return bytes;
}

/// Read the header (everything before the world's state) with @a r into @a checkpoint;
/// @a version receives the file's, @a fingerprint the world's (empty before version 3).
void readHeader(Reader& r, const std::string& path, Checkpoint& checkpoint, uint32_t& version,
                WorldFingerprint& fingerprint)
{
    if (!r.magic())
        throw Error(path, "not an lsdem checkpoint", "give a file written by lsdem-run");
    version = r.pod<uint32_t>();
    if (version < kOldestVersion || version > kVersion)
        throw Error(path, "checkpoint version " + std::to_string(version) + " is not supported",
                    "restart it with the lsdem version that wrote it");
    checkpoint.scenePath = r.text();
    checkpoint.sceneText = r.text();
    checkpoint.timeStep = r.pod<double>();
    checkpoint.record = readRecord(r);
    if (version >= 3) {
        fingerprint.grains = r.words();
        fingerprint.grainAssets = r.words();
        fingerprint.boundaryAssets = r.words();
        if (fingerprint.grainAssets.size() != fingerprint.grains.size()) r.fail();
        if (version < 5) {  // fingerprints of the earlier slope bound: not comparable
            fingerprint.grainAssets.clear();
            fingerprint.boundaryAssets.clear();
        }
    }
    const uint8_t hasEnd = version >= 4 ? r.pod<uint8_t>() : 0;
    if (hasEnd > 1) r.fail();
    if (hasEnd == 1) {
        EndCondition end;
        end.time = r.pod<double>();
        end.steps = r.pod<int64_t>();
        end.boundary = r.pod<int32_t>();
        end.displacement = r.pod<double>();
        const bool sane = std::isfinite(end.time) && end.time >= 0.0 && end.steps >= 0 &&
                          end.boundary >= -1 && std::isfinite(end.displacement) &&
                          end.displacement >= 0.0 && (end.boundary < 0 || end.displacement > 0.0) &&
                          (end.time > 0.0 || end.steps > 0 || end.boundary >= 0);
        if (!sane) r.fail();
        checkpoint.end = end;
    }
}

} // namespace

void saveCheckpoint(const std::string& path, const World& world, const Checkpoint& checkpoint)
{
    writeStreamAtomically(path, [&](std::ostream& out) {
        Writer w(out);
        out.write(kMagic, sizeof kMagic);
        w.pod(kVersion);
        w.text(checkpoint.scenePath);
        w.text(checkpoint.sceneText);
        w.pod(checkpoint.timeStep);
        writeRecord(w, checkpoint.record);
        const WorldFingerprint fingerprint = fingerprintOf(world);
        w.words(fingerprint.grains);
        w.words(fingerprint.grainAssets);
        w.words(fingerprint.boundaryAssets);
        w.pod<uint8_t>(checkpoint.end ? 1 : 0);
        if (checkpoint.end) {
            w.pod(checkpoint.end->time);
            w.pod<int64_t>(checkpoint.end->steps);
            w.pod<int32_t>(checkpoint.end->boundary);
            w.pod(checkpoint.end->displacement);
        }

        w.pod(world.time);
        w.pod<int64_t>(world.step);
        w.pod(world.energy.boundaryWork);
        w.pod(world.energy.initialTotal);
        w.pod<uint64_t>(world.grains.size());
        for (const Grain& g : world.grains) {
            w.vec(g.body.pose.position);
            w.quat(g.body.pose.orientation);
            w.vec(g.body.velocity);
            w.vec(g.body.angularMomentum);
            w.vec(g.force);
            w.vec(g.torque);
        }
        w.pod<uint64_t>(world.boundaries.size());
        for (const Boundary& b : world.boundaries)
            w.vec(b.displacement), w.vec(b.force), w.pod(b.normalStiffness), w.pod(b.normalDashpot);
        // Only histories that hold shear are state: the empty ones are bookkeeping of the
        // contact list, which a restarted run rebuilds.
        uint64_t pairs = 0, boundaryContacts = 0;
        for (const auto& [pair, h] : world.pairHistory) pairs += h.empty() ? 0 : 1;
        for (const auto& [key, h] : world.boundaryHistory) boundaryContacts += h.empty() ? 0 : 1;
        w.pod<uint64_t>(pairs);
        for (const auto& [pair, h] : world.pairHistory) {
            if (h.empty()) continue;
            w.pod<int32_t>(pair.first), w.pod<int32_t>(pair.second);
            w.shear(h.shearOnFirstNodes);
            w.shear(h.shearOnSecondNodes);
        }
        w.pod<uint64_t>(boundaryContacts);
        for (const auto& [key, h] : world.boundaryHistory) {
            if (h.empty()) continue;
            w.pod<int32_t>(key.first), w.pod<int32_t>(key.second);
            w.shear(h);
        }
        out.write(kMagic, sizeof kMagic);  // trailer: a complete file ends with the magic
    });
}

void applyCheckpointEnd(const Checkpoint& checkpoint, Scene& scene, const std::string& path)
{
    if (!checkpoint.end) return;
    if (checkpoint.end->boundary >= static_cast<int>(scene.boundaries.size()))
        throw Error(path, "the checkpoint's end names a boundary its scene lacks",
                    "the checkpoint is damaged: restart from an earlier copy");
    scene.end = *checkpoint.end;
}

bool isCheckpointFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    char magic[sizeof kMagic] = {};
    in.read(magic, sizeof magic);
    return in && std::memcmp(magic, kMagic, sizeof magic) == 0;
}

Checkpoint readCheckpoint(const std::string& path)
{
    return parseCheckpoint(readFileBytes(path), path);
}

Checkpoint parseCheckpoint(std::string bytes, const std::string& path)
{
    Checkpoint c;
    c.fileBytes = std::move(bytes);
    Reader r(c.fileBytes, path);
    uint32_t version = 0;
    WorldFingerprint ignored;
    readHeader(r, path, c, version, ignored);
    return c;
}

void restoreWorldState(const std::string& path, World& world)
{
    restoreWorldState(readCheckpoint(path), path, world);
}

void restoreWorldState(const Checkpoint& checkpoint, const std::string& path, World& world)
{
    // The header again, from the same bytes, to reach the state and the fingerprint.
    Reader r(checkpoint.fileBytes, path);
    Checkpoint header;
    uint32_t version = 0;
    WorldFingerprint fingerprint;
    readHeader(r, path, header, version, fingerprint);
    // The scene's text comes from the checkpoint, but its assets and grain files are read as
    // they are now: they must still make the world the run was checkpointed with.
    if (version >= 3) checkSameInputs(fingerprint, world, path);
    World w = world;  // fill a copy: a failed read leaves @a world untouched
    w.time = r.pod<double>();
    w.step = r.pod<int64_t>();
    w.energy.boundaryWork = r.pod<double>();
    w.energy.initialTotal = r.pod<double>();
    const uint64_t grainBytes = 19 * sizeof(double);  // position, orientation, 4 vectors
    if (r.count(grainBytes) != w.grains.size())
        throw Error(path, "the checkpoint's grain count does not match its scene",
                    "the scene's assets may have changed; start the run again");
    for (Grain& g : w.grains) {
        g.body.pose.position = r.vec();
        g.body.pose.orientation = r.quat();
        g.body.velocity = r.vec();
        g.body.angularMomentum = r.vec();
        g.force = r.vec();
        g.torque = r.vec();
    }
    const bool hasStiffness = version >= 2;
    if (r.count((hasStiffness ? 8 : 6) * sizeof(double)) != w.boundaries.size())
        throw Error(path, "the checkpoint's boundary count does not match its scene",
                    "start the run again");
    for (Boundary& b : w.boundaries) {
        b.displacement = r.vec(), b.force = r.vec();
        b.normalStiffness = hasStiffness ? r.pod<double>() : 0.0;
        b.normalDashpot = hasStiffness ? r.pod<double>() : 0.0;
    }
    // Grain and boundary indices are checked here: a damaged one would index past the world.
    const auto grains = static_cast<int64_t>(w.grains.size());
    const auto boundaries = static_cast<int64_t>(w.boundaries.size());
    w.pairHistory.clear();
    const uint64_t pairs = r.count(2 * sizeof(int32_t) + 2 * sizeof(uint64_t));
    for (uint64_t k = 0; k < pairs; ++k) {
        const int i = r.pod<int32_t>(), j = r.pod<int32_t>();
        if (i < 0 || j <= i || j >= grains) r.fail();  // pairs are kept as (lower, higher)
        PairHistory& h = w.pairHistory[{i, j}];
        h.shearOnFirstNodes = r.shear();
        h.shearOnSecondNodes = r.shear();
    }
    w.boundaryHistory.clear();
    const uint64_t boundaryContacts = r.count(2 * sizeof(int32_t) + sizeof(uint64_t));
    for (uint64_t k = 0; k < boundaryContacts; ++k) {
        const int i = r.pod<int32_t>(), b = r.pod<int32_t>();
        if (i < 0 || i >= grains || b < 0 || b >= boundaries) r.fail();
        w.boundaryHistory[{i, b}] = r.shear();
    }
    if (!r.magic()) r.fail();  // the trailer: a complete file ends with the magic
    world = std::move(w);
}

} // namespace lsdem

#include "lsdem/run/Checkpoint.h"

#include "CheckpointBytes.h"
#include "WorldFingerprint.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

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
/// 6: the record ends with the micromechanics rows (none in an earlier file's).
/// 7: each grain also keeps the energy dissipated by mechanism (DissipatedEnergy) and the
///    periods a periodic cell moved it by (Grain::wrapShift); the world its periodic cell's
///    size, strain rates and stress and the moment its power comes from. An earlier file's
///    grains restart from none, and its energy rows gain empty (NaN) columns for the
///    dissipation.
/// 8: the record ends with each membrane's history rows, and the state with each membrane's
///    (its vertices' positions, velocities and forces, its pressure and energies). An earlier
///    file has none, and restarts a world without membranes only.
/// 9: the record ends with the periodic cell's history rows (none in an earlier file's).
/// 10: each shear spring keeps its stiffness beside its force (ShearHistory::Entry); an
///     earlier file's springs restart with it unknown, and keep their force for one step.
const uint32_t kVersion = 10;
const uint32_t kOldestVersion = 1;

using namespace checkpointbytes;

using Rows = std::vector<std::vector<double>>;

/// History rows: their count, then each row (its own count, its numbers).
void putRows(Writer& w, const Rows& rows)
{
    w.value<uint64_t>(rows.size());
    for (const auto& row : rows) w.numbers(row);
}

/// Rows per boundary or membrane: their count, then each one's rows.
void putRowsPerItem(Writer& w, const std::vector<Rows>& items)
{
    w.value<uint64_t>(items.size());
    for (const Rows& rows : items) putRows(w, rows);
}

void writeRecord(Writer& w, const RunRecord& r)
{
    putRows(w, r.energyRows);
    putRowsPerItem(w, r.boundaryRows);
    w.numbers(r.vtkFrameTimes);
    putRows(w, r.micromechanicsRows);
    putRowsPerItem(w, r.membraneRows);
    putRows(w, r.cellRows);
}

/// A membrane's state: what the scene does not give (its shape as stretched and moving, its
/// forces from the last evaluation, which the next step's first kick and work start from).
void writeMembrane(Writer& w, const Membrane& m)
{
    w.value<uint64_t>(m.positions.size());
    const auto vectors = [&](const std::vector<Vec3>& v) {
        for (size_t i = 0; i < m.positions.size(); ++i)
            putVec(w, i < v.size() ? v[i] : Vec3::Zero());
    };
    vectors(m.positions);
    vectors(m.velocities);
    vectors(m.forces);
    vectors(m.grainForces);
    vectors(m.pressureForces);
    w.number(m.pressure).number(m.targetStress).number(m.strainEnergy);
    w.number(m.rubberOmegaSquared).number(m.dampedWork);
}

/// What putRows and putRowsPerItem wrote (a row is at least its own count).
Rows getRows(Reader& r)
{
    Rows rows(r.count(sizeof(uint64_t)));
    for (auto& row : rows) row = r.numbers();
    return rows;
}

std::vector<Rows> getRowsPerItem(Reader& r)
{
    std::vector<Rows> items(r.count(sizeof(uint64_t)));
    for (Rows& rows : items) rows = getRows(r);
    return items;
}

RunRecord readRecord(Reader& r, uint32_t version)
{
    RunRecord rec;
    rec.energyRows = getRows(r);
    // Written before the dissipation was split by mechanism: those columns unknown.
    if (version < 7)
        for (auto& row : rec.energyRows)
            row.insert(row.end(), 3, std::numeric_limits<double>::quiet_NaN());
    rec.boundaryRows = getRowsPerItem(r);
    rec.vtkFrameTimes = r.numbers();
    if (version >= 6) rec.micromechanicsRows = getRows(r);
    if (version >= 8) rec.membraneRows = getRowsPerItem(r);
    if (version >= 9) rec.cellRows = getRows(r);
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
    if (!r.magic(kMagic))
        throw Error(path, "not an lsdem checkpoint", "give a file written by lsdem-run");
    version = r.value<uint32_t>();
    if (version < kOldestVersion || version > kVersion)
        throw Error(path, "checkpoint version " + std::to_string(version) + " is not supported",
                    "restart it with the lsdem version that wrote it");
    checkpoint.scenePath = r.text();
    checkpoint.sceneText = r.text();
    checkpoint.timeStep = r.value<double>();
    checkpoint.record = readRecord(r, version);
    if (version >= 3) {
        fingerprint.grains = r.list<uint64_t>();
        fingerprint.grainAssets = r.list<uint64_t>();
        fingerprint.boundaryAssets = r.list<uint64_t>();
        if (fingerprint.grainAssets.size() != fingerprint.grains.size()) r.fail();
        if (version < 5) {  // fingerprints of the earlier slope bound: not comparable
            fingerprint.grainAssets.clear();
            fingerprint.boundaryAssets.clear();
        }
    }
    const uint8_t hasEnd = version >= 4 ? r.value<uint8_t>() : 0;
    if (hasEnd > 1) r.fail();
    if (hasEnd == 1) {
        EndCondition end;
        end.time = r.value<double>();
        end.steps = r.value<int64_t>();
        end.boundary = r.value<int32_t>();
        end.displacement = r.value<double>();
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
    std::string bytes;
    Writer w(bytes);
    w.raw(kMagic, sizeof kMagic);
    {
        w.value(kVersion);
        w.text(checkpoint.scenePath);
        w.text(checkpoint.sceneText);
        w.value(checkpoint.timeStep);
        writeRecord(w, checkpoint.record);
        const WorldFingerprint fingerprint = fingerprintOf(world);
        w.list(fingerprint.grains);
        w.list(fingerprint.grainAssets);
        w.list(fingerprint.boundaryAssets);
        w.value<uint8_t>(checkpoint.end ? 1 : 0);
        if (checkpoint.end) {
            w.value(checkpoint.end->time);
            w.value<int64_t>(checkpoint.end->steps);
            w.value<int32_t>(checkpoint.end->boundary);
            w.value(checkpoint.end->displacement);
        }

        w.value(world.time);
        w.value<int64_t>(world.step);
        w.value(world.energy.boundaryWork);
        w.value(world.energy.initialTotal);
        putVec(w, world.periodic.size);
        putVec(w, world.periodic.strainRate);  // a stress-controlled axis's changes
        putVec(w, world.periodic.stress);
        putVec(w, world.energy.cellMoment);
        w.value<uint64_t>(world.grains.size());
        for (const Grain& g : world.grains) {
            putVec(w, g.body.pose.position);
            putQuat(w, g.body.pose.orientation);
            putVec(w, g.body.velocity);
            putVec(w, g.body.angularMomentum);
            putVec(w, g.force);
            putVec(w, g.torque);
            w.number(g.dissipated.friction).number(g.dissipated.dashpot).number(
                g.dissipated.globalDamping);
            putVec(w, g.wrapShift);
        }
        w.value<uint64_t>(world.boundaries.size());
        for (const Boundary& b : world.boundaries)
            putVec(w, b.displacement), putVec(w, b.force), w.value(b.normalStiffness), w.value(b.normalDashpot);
        w.value<uint64_t>(world.membranes.size());
        for (const Membrane& m : world.membranes) writeMembrane(w, m);
        // Only histories that hold shear are state: the empty ones are bookkeeping of the
        // contact list, which a restarted run rebuilds.
        uint64_t pairs = 0, boundaryContacts = 0;
        for (const auto& [pair, h] : world.pairHistory) pairs += h.empty() ? 0 : 1;
        for (const auto& [key, h] : world.boundaryHistory) boundaryContacts += h.empty() ? 0 : 1;
        w.value<uint64_t>(pairs);
        for (const auto& [pair, h] : world.pairHistory) {
            if (h.empty()) continue;
            w.value<int32_t>(pair.first), w.value<int32_t>(pair.second);
            putShear(w, h.shearOnFirstNodes);
            putShear(w, h.shearOnSecondNodes);
        }
        w.value<uint64_t>(boundaryContacts);
        for (const auto& [key, h] : world.boundaryHistory) {
            if (h.empty()) continue;
            w.value<int32_t>(key.first), w.value<int32_t>(key.second);
            putShear(w, h);
        }
        w.raw(kMagic, sizeof kMagic);  // trailer: a complete file ends with the magic
    }
    writeStreamAtomically(path, [&](std::ostream& out) {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
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
    try {
        readHeader(r, path, c, version, ignored);
    } catch (const DamagedBytes&) {
        r.fail();
    }
    return c;
}

void restoreWorldState(const std::string& path, World& world)
{
    restoreWorldState(readCheckpoint(path), path, world);
}

namespace {

// The world's state follows the header in the order saveCheckpoint writes it: the clock and
// energies, the periodic cell, the grains, the boundaries, then the shear histories. Each
// reader below takes its part and checks it, so that a damaged file never starts a run.

/// The clock and the energies the run carries (time, step, boundary work, initial total).
void readClock(Reader& r, World& w)
{
    w.time = r.value<double>();
    w.step = r.value<int64_t>();
    w.energy.boundaryWork = r.value<double>();
    w.energy.initialTotal = r.value<double>();
    if (!std::isfinite(w.time) || w.step < 0 || !std::isfinite(w.energy.boundaryWork) ||
        !std::isfinite(w.energy.initialTotal))
        r.fail();
}

/// The cell as the run left it (version 7 on): periodic along the axes the scene makes
/// periodic.
void readPeriodicCell(Reader& r, const std::string& path, World& w)
{
    const Vec3 size = r.vec();
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(size[a]) || size[a] < 0.0 || (size[a] > 0.0) != w.periodic.periodic(a))
            throw Error(path, "the checkpoint's periodic cell does not match its scene's",
                        "the scene's periodic_cell may have changed; start the run again");
    w.periodic.size = size;
    w.periodic.strainRate = r.vec();
    w.periodic.stress = r.vec();
    w.energy.cellMoment = r.vec();
    if (!allFinite(w.periodic.strainRate) || !allFinite(w.periodic.stress) ||
        !allFinite(w.energy.cellMoment))
        r.fail();
}

/// One grain's motion and forces (and from version 7 its dissipated energies and the periods
/// it moved by; an earlier file's grain restarts from none).
void readGrain(Reader& r, uint32_t version, Grain& g)
{
    g.body.pose.position = r.vec();
    g.body.pose.orientation = r.quat();
    g.body.velocity = r.vec();
    g.body.angularMomentum = r.vec();
    g.force = r.vec();
    g.torque = r.vec();
    g.dissipated = DissipatedEnergy();
    g.wrapShift = Vec3::Zero();
    if (version >= 7) {
        g.dissipated.friction = r.number();
        g.dissipated.dashpot = r.number();
        g.dissipated.globalDamping = r.number();
        g.wrapShift = r.vec();
    }
    // A damaged state must not start a run: every number finite, the rotation a rotation.
    const bool sane = allFinite(g.body.pose.position) && allFinite(g.body.velocity) &&
                      allFinite(g.body.angularMomentum) && allFinite(g.force) &&
                      allFinite(g.torque) && std::isfinite(g.dissipated.friction) &&
                      std::isfinite(g.dissipated.dashpot) &&
                      std::isfinite(g.dissipated.globalDamping) && allFinite(g.wrapShift) &&
                      std::abs(g.body.pose.orientation.norm() - 1.0) < 1e-6;
    if (!sane) r.fail();
}

/// Every grain, as many as the scene makes.
void readGrains(Reader& r, const std::string& path, uint32_t version, World& w)
{
    // position, orientation, 4 vectors (and from version 7, 3 dissipated energies and the
    // periods moved by)
    const uint64_t grainBytes = (version >= 7 ? 25 : 19) * sizeof(double);
    if (r.count(grainBytes) != w.grains.size())
        throw Error(path, "the checkpoint's grain count does not match its scene",
                    "the scene's assets may have changed; start the run again");
    for (Grain& g : w.grains) readGrain(r, version, g);
}

/// Every boundary's displacement and force (and from version 2 its contact stiffness and
/// dashpot, a servo wall's gain).
void readBoundaries(Reader& r, const std::string& path, uint32_t version, World& w)
{
    const bool hasStiffness = version >= 2;
    if (r.count((hasStiffness ? 8 : 6) * sizeof(double)) != w.boundaries.size())
        throw Error(path, "the checkpoint's boundary count does not match its scene",
                    "start the run again");
    for (Boundary& b : w.boundaries) {
        b.displacement = r.vec(), b.force = r.vec();
        b.normalStiffness = hasStiffness ? r.value<double>() : 0.0;
        b.normalDashpot = hasStiffness ? r.value<double>() : 0.0;
        if (!allFinite(b.displacement) || !allFinite(b.force) ||
            !std::isfinite(b.normalStiffness) || !std::isfinite(b.normalDashpot))
            r.fail();
    }
}

/// Every membrane's state (version 8 on), as many as the scene makes, each with as many
/// vertices.
void readMembranes(Reader& r, const std::string& path, uint32_t version, World& w)
{
    const uint64_t count = version >= 8 ? r.count(sizeof(uint64_t) + 5 * sizeof(double)) : 0;
    if (count != w.membranes.size())
        throw Error(path, "the checkpoint holds " + std::to_string(count) +
                              " membranes and its scene makes " +
                              std::to_string(w.membranes.size()),
                    version < 8 ? "the checkpoint predates membranes: start the run again"
                                : "the scene's [[membranes]] may have changed; start the run again");
    for (Membrane& m : w.membranes) {
        if (r.count(15 * sizeof(double)) != m.positions.size())
            throw Error(path, "the checkpoint's membrane '" + m.name + "' has another number "
                              "of vertices than its scene makes",
                        "the scene's [[membranes]] may have changed; start the run again");
        const auto vectors = [&](std::vector<Vec3>& v) {
            v.resize(m.positions.size());
            for (Vec3& x : v) {
                x = r.vec();
                if (!allFinite(x)) r.fail();
            }
        };
        vectors(m.positions);
        vectors(m.velocities);
        vectors(m.forces);
        vectors(m.grainForces);
        vectors(m.pressureForces);
        m.pressure = r.number();
        m.targetStress = r.number();
        m.strainEnergy = r.number();
        m.rubberOmegaSquared = r.number();
        m.dampedWork = r.number();
        if (!(std::isfinite(m.pressure) && m.pressure >= 0.0) || !std::isfinite(m.targetStress) ||
            !std::isfinite(m.strainEnergy) || !std::isfinite(m.rubberOmegaSquared) ||
            !std::isfinite(m.dampedWork))
            r.fail();
    }
}

/// The shear histories that hold shear, of grain pairs and of grains on boundaries. Grain and
/// boundary indices are checked here: a damaged one would index past the world.
void readShearHistories(Reader& r, World& w, uint32_t version)
{
    const auto grains = static_cast<int64_t>(w.grains.size());
    const auto boundaries = static_cast<int64_t>(w.boundaries.size());
    const bool withStiffness = version >= 10;
    w.pairHistory.clear();
    const uint64_t pairs = r.count(2 * sizeof(int32_t) + 2 * sizeof(uint64_t));
    for (uint64_t k = 0; k < pairs; ++k) {
        const int i = r.value<int32_t>(), j = r.value<int32_t>();
        if (i < 0 || j <= i || j >= grains) r.fail();  // pairs are kept as (lower, higher)
        PairHistory& h = w.pairHistory[{i, j}];
        h.shearOnFirstNodes = r.shear(withStiffness);
        h.shearOnSecondNodes = r.shear(withStiffness);
    }
    w.boundaryHistory.clear();
    const uint64_t boundaryContacts = r.count(2 * sizeof(int32_t) + sizeof(uint64_t));
    for (uint64_t k = 0; k < boundaryContacts; ++k) {
        const int i = r.value<int32_t>(), b = r.value<int32_t>();
        if (i < 0 || i >= grains || b < 0 || b >= boundaries) r.fail();
        w.boundaryHistory[{i, b}] = r.shear(withStiffness);
    }
}

/// @a world with the state that @a r (at the start of the checkpoint's bytes) holds.
World stateFrom(Reader& r, const std::string& path, const World& world)
{
    // The header again, from the same bytes, to reach the state and the fingerprint.
    Checkpoint header;
    uint32_t version = 0;
    WorldFingerprint fingerprint;
    readHeader(r, path, header, version, fingerprint);
    // The scene's text comes from the checkpoint, but its assets and grain files are read as
    // they are now: they must still make the world the run was checkpointed with.
    if (version >= 3) checkSameInputs(fingerprint, world, path);
    World w = world;
    readClock(r, w);
    if (version >= 7) readPeriodicCell(r, path, w);
    readGrains(r, path, version, w);
    readBoundaries(r, path, version, w);
    readMembranes(r, path, version, w);
    readShearHistories(r, w, version);
    if (!r.magic(kMagic)) r.fail();  // the trailer: a complete file ends with the magic
    return w;
}

} // namespace

void restoreWorldState(const Checkpoint& checkpoint, const std::string& path, World& world)
{
    Reader r(checkpoint.fileBytes, path);
    try {
        world = stateFrom(r, path, world);  // a failed read leaves @a world untouched
    } catch (const DamagedBytes&) {
        r.fail();
    }
}

} // namespace lsdem

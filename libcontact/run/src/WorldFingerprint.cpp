#include "WorldFingerprint.h"

#include "lsdem/ls/Error.h"

#include <cstring>
#include <map>

namespace lsdem {

namespace {

/// A 64-bit hash of words fed one at a time (numbers bit for bit). Not cryptographic: it
/// tells a changed input from an unchanged one, nothing more.
class Hash
{
public:
    void word(uint64_t w)
    {
        mState = (mState ^ w) * 0x100000001b3ULL;
        mState ^= mState >> 29;
    }
    void number(double d)
    {
        uint64_t bits = 0;
        std::memcpy(&bits, &d, sizeof bits);
        word(bits);
    }
    void vector(const Vec3& v) { number(v.x()), number(v.y()), number(v.z()); }
    void text(const std::string& s)
    {
        word(s.size());
        for (unsigned char c : s) word(c);
    }
    uint64_t value() const { return mState; }

private:
    uint64_t mState = 0xcbf29ce484222325ULL;
};

/// What a simulation reads of an asset. The level set enters through what is derived from
/// it (the inside box and the slope bound) and through the mass properties and nodes baked
/// with it, so a rebaked or replaced asset changes the number.
uint64_t assetFingerprint(const GrainAsset& a)
{
    Hash h;
    h.number(a.voxelSize);
    h.number(a.mass.volume);
    for (int i = 0; i < 9; ++i) h.number(a.mass.inertia(i / 3, i % 3));
    h.number(a.boundingRadius);
    h.vector(a.insideBoxMin);
    h.vector(a.insideBoxMax);
    h.number(a.levelSetSlope);
    h.word(a.nodes.size());
    for (const Vec3& p : a.nodes.positions) h.vector(p);
    for (double area : a.nodes.areas) h.number(area);
    return h.value();
}

} // namespace

WorldFingerprint fingerprintOf(const World& world)
{
    WorldFingerprint f;
    std::map<const GrainAsset*, uint64_t> indexOf;
    for (size_t k = 0; k < world.assets.size(); ++k) {
        f.assets.push_back(world.assets[k] ? assetFingerprint(*world.assets[k]) : 0);
        indexOf.emplace(world.assets[k].get(), k);
    }
    for (const Grain& g : world.grains) {
        Hash h;
        h.text(g.name);
        const auto it = indexOf.find(g.asset.get());
        h.word(it != indexOf.end() ? it->second : ~uint64_t(0));
        h.word(static_cast<uint64_t>(g.material));
        h.word(static_cast<uint64_t>(g.motion));
        h.number(g.body.mass);
        h.vector(g.body.principalInertia);
        f.grains.push_back(h.value());
    }
    return f;
}

void checkSameInputs(const WorldFingerprint& stored, const World& world, const std::string& path)
{
    const WorldFingerprint now = fingerprintOf(world);
    const std::string fix =
        "restore the files the run was started with, or start the run again from its scene";
    if (now.assets.size() != stored.assets.size())
        throw Error(path,
                    "the scene now makes " + std::to_string(now.assets.size()) +
                        " assets, the checkpointed run had " +
                        std::to_string(stored.assets.size()) + " (an asset set changed?)",
                    fix);
    for (size_t k = 0; k < now.assets.size(); ++k)
        if (now.assets[k] != stored.assets[k]) {
            const std::string source =
                world.assets[k] ? " (from '" + world.assets[k]->provenance.source + "')" : "";
            throw Error(path,
                        "asset " + std::to_string(k) + source +
                            " is not the one the run was checkpointed with: its file, mesh or "
                            "bake options changed since, so a restart would not continue the "
                            "same run",
                        fix);
        }
    if (now.grains.size() != stored.grains.size())
        throw Error(path,
                    "the scene now has " + std::to_string(now.grains.size()) +
                        " grains, the checkpointed run had " +
                        std::to_string(stored.grains.size()) + " (a grain file changed?)",
                    fix);
    for (size_t k = 0; k < now.grains.size(); ++k)
        if (now.grains[k] != stored.grains[k])
            throw Error(path,
                        "grain " + std::to_string(k) + " ('" + world.grains[k].name +
                            "') is not the one the run was checkpointed with: its name, asset, "
                            "material, motion or mass changed since (a grain file or catalogue "
                            "edited?)",
                        fix);
}

} // namespace lsdem

#include "WorldFingerprint.h"

#include "lsdem/core/Error.h"

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
    std::map<const GrainAsset*, uint64_t> assetNumbers;  // grains share assets: each once
    auto numberOf = [&](const std::shared_ptr<const GrainAsset>& asset) -> uint64_t {
        if (!asset) return 0;
        const auto [it, fresh] = assetNumbers.emplace(asset.get(), 0);
        if (fresh) it->second = assetFingerprint(*asset);
        return it->second;
    };
    for (const Grain& g : world.grains) {
        Hash h;
        h.text(g.name);
        h.word(static_cast<uint64_t>(g.material));
        h.word(static_cast<uint64_t>(g.motion));
        h.number(g.body.mass);
        h.vector(g.body.principalInertia);
        f.grains.push_back(h.value());
        f.grainAssets.push_back(numberOf(g.asset));
    }
    for (const Boundary& b : world.boundaries) f.boundaryAssets.push_back(numberOf(b.asset));
    return f;
}

void checkSameInputs(const WorldFingerprint& stored, const World& world, const std::string& path)
{
    const WorldFingerprint now = fingerprintOf(world);
    auto refuse = [&](const std::string& problem) {
        throw Error(path, problem,
                    "restore the files the run was started with, or start the run again from "
                    "its scene");
    };
    if (now.grains.size() != stored.grains.size())
        refuse("the scene now has " + std::to_string(now.grains.size()) +
               " grains, the checkpointed run had " + std::to_string(stored.grains.size()) +
               " (a grain file changed?)");
    for (size_t k = 0; k < now.grains.size(); ++k) {
        const std::string grain = "grain " + std::to_string(k) + " ('" + world.grains[k].name + "')";
        if (!stored.grainAssets.empty() && now.grainAssets[k] != stored.grainAssets[k])
            refuse(grain + ": its asset is not the one the run was checkpointed with (its file or "
                           "mesh changed since), so a restart would not continue the same run");
        if (now.grains[k] != stored.grains[k])
            refuse(grain + " is not the one the run was checkpointed with: its name, material, "
                           "motion or mass changed since (a grain file or catalogue edited?)");
    }
    // (The scene's text, and so its boundaries, come from the checkpoint.)
    for (size_t b = 0; b < now.boundaryAssets.size() && b < stored.boundaryAssets.size(); ++b)
        if (now.boundaryAssets[b] != stored.boundaryAssets[b])
            refuse("boundary '" + world.boundaries[b].name +
                   "': its level set is not the one the run was checkpointed with (its file or "
                   "mesh changed since)");
}

} // namespace lsdem

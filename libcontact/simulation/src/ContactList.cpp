#include "lsdem/simulation/ContactList.h"

#include "lsdem/simulation/BroadPhase.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <stdexcept>
#include <tuple>

namespace lsdem {

bool ContactList::needsRebuild(const World& world) const
{
    const bool sizesChanged = mGrainPositionsAtBuild.size() != world.grains.size() ||
                              mBoundaryDisplacementsAtBuild.size() != world.boundaries.size();
    if (!mBuilt || sizesChanged) return true;
    // Two bodies within reach now were within reach plus the skin at the build as long as
    // neither moved more than half of it.
    const double half2 = 0.25 * mSkin * mSkin;
    // Checked for every grain every step: in parallel (any one moved too far decides).
    bool stale = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, world.grains.size(), 256), false,
        [&](const tbb::blocked_range<size_t>& r, bool moved) {
            for (size_t i = r.begin(); !moved && i != r.end(); ++i)
                moved = (world.grains[i].body.pose.position - mGrainPositionsAtBuild[i])
                            .squaredNorm() > half2;
            return moved;
        },
        [](bool a, bool b) { return a || b; });
    for (size_t b = 0; !stale && b < world.boundaries.size(); ++b)
        stale = (world.boundaries[b].displacement - mBoundaryDisplacementsAtBuild[b])
                    .squaredNorm() > half2;
    return stale;
}

bool ContactList::update(World& world)
{
    const bool sizesChanged = mGrainPositionsAtBuild.size() != world.grains.size() ||
                              mBoundaryDisplacementsAtBuild.size() != world.boundaries.size();
    const bool stale = needsRebuild(world);
    // Built and only moved since: the same grains and assets, so what each pair learned about
    // its node blocks still applies.
    if (stale) rebuild(world, mRenumbered || (mBuilt && !sizesChanged));
    mRenumbered = false;
    return stale;
}

void ContactList::renumber(const std::vector<int>& newIndex)
{
    // The order is kept, so the pairs that remain stay sorted; the rebuild takes their node
    // blocks (valid for the same two grains) and points them into the world's new histories.
    size_t kept = 0;
    for (size_t k = 0; k < mPairSlots; ++k) {
        ContactSlot& s = mSlots[k];
        const int first = newIndex[size_t(s.first)], second = newIndex[size_t(s.second)];
        if (first < 0 || second < 0) continue;
        s.first = first;
        s.second = second;
        s.pairHistory = nullptr;
        if (kept != k) mSlots[kept] = std::move(s);
        ++kept;
    }
    mSlots.resize(kept);
    mPairSlots = kept;
    mBuilt = false;
    mRenumbered = true;
}

double ContactList::skinFor(const World& w) const
{
    if (w.grains.empty()) return 0.0;
    // A fraction of the median grain, so a polydisperse packing rebuilds when its typical
    // grain, not its largest, has moved a fraction of its size.
    std::vector<double> sorted;
    sorted.reserve(w.grains.size());
    for (const Grain& g : w.grains) sorted.push_back(g.asset->boundingRadius);
    const size_t half = sorted.size() / 2;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(half), sorted.end());
    return mSkinFraction * sorted[half];
}

namespace {

using GrainPair = std::pair<int, int>;

/// Slot @a s takes the knowledge (its node blocks near the other body and its force buffers)
/// of the previous slot with the same @a key (keyOf of it), found by advancing @a cursor
/// through previous[cursor, end), sorted by that key.
template <class KeyOf>
void inheritKnowledge(ContactSlot& s, std::vector<ContactSlot>& previous, size_t& cursor,
                      size_t end, const GrainPair& key, KeyOf keyOf)
{
    while (cursor < end && keyOf(previous[cursor]) < key) ++cursor;
    if (cursor < end && keyOf(previous[cursor]) == key) {
        s.candidates = std::move(previous[cursor].candidates);
        s.forces.swap(previous[cursor].forces);
    }
}

/// A candidate grain pair and the periods by which its second grain's image is moved (a
/// periodic cell's; zero inside).
struct ShiftedPair
{
    GrainPair pair;
    Vec3 periods = Vec3::Zero();
};

/// A grain's copy one period away along some periodic axes: which grain, and how many periods
/// (−1, 0 or 1) along each axis.
struct Image
{
    int grain = 0;
    Vec3 periods = Vec3::Zero();
};

/// The images of @a centers that come within @a reach of the cell: for each grain, its copies
/// shifted by ±1 period along each periodic axis and their combinations (edges, corners), in
/// grain order.
std::vector<Image> imagesNear(const PeriodicCell& cell, const std::vector<Vec3>& centers,
                              double reach)
{
    std::vector<Image> images;
    for (size_t i = 0; i < centers.size(); ++i)
        for (const Vec3& periods : cell.imagePeriodsNear(centers[i], reach))
            images.push_back({int(i), periods});
    return images;
}

/// The candidate pairs of @a w's grains (centres @a centers, bounding radii @a radii) within
/// @a skin, sorted; in a periodic cell with their images too, each pair once, touching the
/// nearest image (the cell is at least twice any pair's reach: BuildWorld checks it).
std::vector<ShiftedPair> candidatePairs(const World& w, const std::vector<Vec3>& centers,
                                        const std::vector<double>& radii, double skin)
{
    std::vector<ShiftedPair> pairs;
    if (!w.periodic.active()) {
        for (const GrainPair& p : findCandidatePairs(centers, radii, skin)) pairs.push_back({p});
        return pairs;
    }
    const int n = static_cast<int>(centers.size());
    double largest = 0.0;
    for (double r : radii) largest = std::max(largest, r);
    const std::vector<Image> images = imagesNear(w.periodic, centers, 2.0 * largest + skin);
    std::vector<Vec3> all = centers;
    std::vector<double> allRadii = radii;
    for (const Image& image : images) {
        all.push_back(centers[size_t(image.grain)] + w.periodic.imageShift(image.periods));
        allRadii.push_back(radii[size_t(image.grain)]);
    }
    for (const GrainPair& p : findCandidatePairs(all, allRadii, skin)) {
        if (p.first >= n) continue;  // two images: their grains meet as a grain and an image
        if (p.second < n) {
            pairs.push_back({p});
            continue;
        }
        const Image& image = images[size_t(p.second - n)];
        if (image.grain == p.first) continue;  // a grain and its own image: the cell is too small
        if (p.first < image.grain)
            pairs.push_back({{p.first, image.grain}, image.periods});
        else
            pairs.push_back({{image.grain, p.first}, Vec3(-image.periods)});
    }
    // A pair across a face is found from both of its grains' images: once.
    const auto key = [](const ShiftedPair& p) {
        return std::make_tuple(p.pair.first, p.pair.second, p.periods.x(), p.periods.y(), p.periods.z());
    };
    std::sort(pairs.begin(), pairs.end(),
              [&](const ShiftedPair& a, const ShiftedPair& b) { return key(a) < key(b); });
    pairs.erase(std::unique(pairs.begin(), pairs.end(),
                            [&](const ShiftedPair& a, const ShiftedPair& b) { return key(a) == key(b); }),
                pairs.end());
    for (size_t k = 1; k < pairs.size(); ++k)
        if (pairs[k].pair == pairs[k - 1].pair)
            throw std::logic_error("ContactList: a pair touches two images (the periodic cell is "
                                   "smaller than twice a pair's reach)");
    return pairs;
}

/// Append a slot per pair of @a pairs (sorted) to @a slots, walking the sorted histories along:
/// histories of pairs no longer listed are dropped, new pairs start empty. std::map nodes do
/// not move, so the slots can point into the map until the next rebuild. A pair still listed
/// keeps what it knew from previous[0, previousPairs).
void makePairSlots(World& w, const std::vector<ShiftedPair>& pairs, std::vector<ContactSlot>& slots,
                   std::vector<ContactSlot>& previous, size_t previousPairs)
{
    const auto pairOf = [](const ContactSlot& o) { return GrainPair(o.first, o.second); };
    size_t kept = 0;
    auto it = w.pairHistory.begin();
    for (const auto& [p, periods] : pairs) {
        while (it != w.pairHistory.end() && it->first < p) it = w.pairHistory.erase(it);
        if (it == w.pairHistory.end() || it->first != p)
            it = w.pairHistory.emplace_hint(it, p, PairHistory{});
        ContactSlot& s = slots.emplace_back();
        s.first = p.first;
        s.second = p.second;
        s.periods = periods;
        s.pairHistory = &it->second;
        inheritKnowledge(s, previous, kept, previousPairs, p, pairOf);
        ++it;
    }
    w.pairHistory.erase(it, w.pairHistory.end());
}

/// The same for grain–boundary slots, sorted by grain, then boundary (@a nearBoundaries per
/// grain): a level-set obstacle's slot keeps the grain's nodes near it, from
/// previous[previousPairs, end).
void makeBoundarySlots(World& w, const std::vector<std::vector<int>>& nearBoundaries,
                       std::vector<ContactSlot>& slots, std::vector<ContactSlot>& previous,
                       size_t previousPairs)
{
    const auto grainAndBoundaryOf = [](const ContactSlot& o) { return GrainPair(o.first, o.boundary); };
    auto it = w.boundaryHistory.begin();
    size_t kept = previousPairs;
    for (size_t i = 0; i < nearBoundaries.size(); ++i)
        for (int b : nearBoundaries[i]) {
            const GrainPair key(static_cast<int>(i), b);
            while (it != w.boundaryHistory.end() && it->first < key) it = w.boundaryHistory.erase(it);
            if (it == w.boundaryHistory.end() || it->first != key)
                it = w.boundaryHistory.emplace_hint(it, key, ShearHistory{});
            ContactSlot& s = slots.emplace_back();
            s.first = key.first;
            s.boundary = b;
            s.boundaryHistory = &it->second;
            inheritKnowledge(s, previous, kept, previous.size(), key, grainAndBoundaryOf);
            ++it;
        }
    w.boundaryHistory.erase(it, w.boundaryHistory.end());
}

/// Each grain's slots in list order (a grain's forces are summed in this order): @a starts
/// (n + 1 entries) into @a refs.
void indexSlotsByGrain(const std::vector<ContactSlot>& slots, int n, std::vector<size_t>& starts,
                       std::vector<GrainSlotRef>& refs)
{
    starts.assign(size_t(n) + 1, 0);
    for (const ContactSlot& s : slots) {
        ++starts[size_t(s.first) + 1];
        if (s.boundary < 0) ++starts[size_t(s.second) + 1];
    }
    for (int i = 0; i < n; ++i) starts[size_t(i) + 1] += starts[size_t(i)];
    refs.resize(starts.back());
    std::vector<size_t> fill(starts.begin(), starts.end() - 1);
    for (size_t k = 0; k < slots.size(); ++k) {
        const ContactSlot& s = slots[k];
        refs[fill[size_t(s.first)]++] = {static_cast<int>(k), true};
        if (s.boundary < 0) refs[fill[size_t(s.second)]++] = {static_cast<int>(k), false};
    }
}

} // namespace

void ContactList::rebuild(World& w, bool keepPairKnowledge)
{
    const int n = static_cast<int>(w.grains.size());
    std::vector<Vec3> centers(static_cast<size_t>(n));
    std::vector<double> radii(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        centers[size_t(i)] = w.grains[size_t(i)].body.pose.position;
        radii[size_t(i)] = w.grains[size_t(i)].asset->boundingRadius;
    }
    if (mFixedSkin >= 0.0)
        mSkin = mFixedSkin;
    else if (n > 0)
        mSkin = skinFor(w);

    // Grain pairs whose spheres come within the skin (kinematic pairs too, so their forces
    // are recorded), and the boundaries each grain may touch within the skin, found in
    // parallel and joined in grain order (sorted as if found serially).
    std::vector<ShiftedPair> pairs = candidatePairs(w, centers, radii, mSkin);
    if (mOwned) {  // only the pairs this rank evaluates
        const std::vector<char>& owned = *mOwned;
        pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                                   [&](const ShiftedPair& p) {
                                       return !owned[size_t(p.pair.first)] &&
                                              !owned[size_t(p.pair.second)];
                                   }),
                    pairs.end());
    }
    const int boundaryCount = static_cast<int>(w.boundaries.size());
    std::vector<std::vector<int>> nearBoundaries(static_cast<size_t>(n));
    tbb::parallel_for(0, n, [&](int i) {
        if (mOwned && !(*mOwned)[size_t(i)]) return;
        for (int b = 0; b < boundaryCount; ++b)
            if (w.boundaries[size_t(b)].mayTouch(centers[size_t(i)], radii[size_t(i)] + mSkin))
                nearBoundaries[size_t(i)].push_back(b);
    });

    // The slots, pairs then grain–boundary, each keeping its history and (after motion) what
    // it knew, so a rebuild costs its pairs no full walk of their blocks.
    std::vector<ContactSlot> previous;
    if (keepPairKnowledge) previous.swap(mSlots);
    const size_t previousPairs = keepPairKnowledge ? mPairSlots : 0;
    mSlots.clear();
    mSlots.reserve(pairs.size() + previous.size() - previousPairs);
    makePairSlots(w, pairs, mSlots, previous, previousPairs);
    mPairSlots = mSlots.size();
    makeBoundarySlots(w, nearBoundaries, mSlots, previous, previousPairs);
    indexSlotsByGrain(mSlots, n, mGrainSlotStart, mGrainSlots);

    mGrainPositionsAtBuild = centers;
    mBoundaryDisplacementsAtBuild.clear();
    for (const Boundary& b : w.boundaries) mBoundaryDisplacementsAtBuild.push_back(b.displacement);
    mBuilt = true;
    ++mRebuilds;
}


} // namespace lsdem

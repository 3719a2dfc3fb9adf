// One simulation split by space over ranks without MPI: the sub-domains of the recursive
// bisection against hand-computed cuts and balance bounds, and the whole decomposition
// (GhostDecomposition.h) run on "ranks" that are threads of this process (a RankGroup whose
// collectives are a barrier and shared buffers), each owning its sub-domain's grains with
// ghosts of its neighbours': the world gathered from them must be bit for bit where one
// process ends, for 1 to 4 ranks, with a rank that owns nothing, across a restart, and with
// shear history that must travel between ranks as grains cross sub-domains.
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/GhostDecomposition.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/simulation/WorkBisection.h"
#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <iostream>
#include <mutex>
#include <random>
#include <set>
#include <thread>

using namespace lsdem;

namespace {

// ---------------------------------------------------------------------------------------------
// The bisection.
// ---------------------------------------------------------------------------------------------

/// Total weight of each part.
std::vector<double> partWeights(const WorkBisection& b, const std::vector<Vec3>& points,
                                const std::vector<double>& weights)
{
    std::vector<double> w(size_t(b.parts()), 0.0);
    for (size_t i = 0; i < points.size(); ++i) w[size_t(b.partOf(points[i]))] += weights[i];
    return w;
}

} // namespace

// 100 points of equal weight on a line at x = 0..99 in 4 parts: the cuts fall at the quartiles
// (between 24 and 25, 49 and 50, 74 and 75), and the parts are numbered along the line; the
// parts within a reach of a point are those the cube around it meets.
TEST(WorkBisection, EqualWeightsOnALineCutAtTheQuartiles)
{
    std::vector<Vec3> points;
    for (int i = 0; i < 100; ++i) points.emplace_back(double(i), 0.01 * (i % 3), 0.0);
    const WorkBisection b = WorkBisection::balance(points, std::vector<double>(100, 1.0), 4);
    ASSERT_EQ(b.parts(), 4);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(b.partOf(points[size_t(i)]), i / 25) << i;
    // Space beyond the points belongs to the outer parts; a point between two grains to one.
    EXPECT_EQ(b.partOf(Vec3(-1e9, 0, 0)), 0);
    EXPECT_EQ(b.partOf(Vec3(1e9, 0, 0)), 3);
    EXPECT_EQ(b.partOf(Vec3(24.6, 5, 5)), 1);
    // The parts within reach (the ghosts' test): across the cut at 24.5 or not.
    std::vector<int> near;
    b.partsNear(Vec3(24.6, 0, 0), 0.5, near);
    EXPECT_EQ(near, (std::vector<int>{0, 1}));
    b.partsNear(Vec3(24.6, 0, 0), 0.05, near);
    EXPECT_EQ(near, (std::vector<int>{1}));
    b.partsNear(Vec3(50, 0, 0), 30.0, near);
    EXPECT_EQ(near, (std::vector<int>{0, 1, 2, 3}));
}

// Random points with random weights: every part's work is the mean within what one cut can
// miss. A cut misses its share by at most half the heaviest point, and a part lies below at
// most ceil(log2 P) cuts, each of whose miss is shared by fewer parts; so each part's work is
// within mean ± levels × heaviest of the mean.
TEST(WorkBisection, RandomWeightsAreSplitEvenly)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec3> points;
    std::vector<double> weights;
    for (int i = 0; i < 2000; ++i) {
        points.emplace_back(10.0 * u(rng), 3.0 * u(rng), 5.0 * u(rng));
        weights.push_back(1.0 + 100.0 * u(rng) * u(rng));
    }
    const double heaviest = *std::max_element(weights.begin(), weights.end());
    double total = 0.0;
    for (double w : weights) total += w;
    for (int parts : {1, 2, 3, 4, 5, 7, 8}) {
        const WorkBisection b = WorkBisection::balance(points, weights, parts);
        const std::vector<double> w = partWeights(b, points, weights);
        const double mean = total / parts;
        const double levels = std::ceil(std::log2(double(parts)));
        for (int p = 0; p < parts; ++p)
            EXPECT_NEAR(w[size_t(p)], mean, levels * heaviest + 1e-9)
                << parts << " parts, part " << p;
        // The same input gives the same cuts (every rank draws them itself).
        const WorkBisection again = WorkBisection::balance(points, weights, parts);
        for (const Vec3& p : points) ASSERT_EQ(again.partOf(p), b.partOf(p));
    }
}

// The cut follows the work, not the count: 10 points of weight 50 at the left end of a line
// of 100 points (the rest weigh 1; total 590) split in two where the left side's work is
// closest to 295: after 6 heavy points (300; 5 heavy points would give 250), so 6 points on
// one side and 94 on the other.
TEST(WorkBisection, TheCutFollowsTheWorkNotTheCount)
{
    std::vector<Vec3> points;
    std::vector<double> weights;
    for (int i = 0; i < 100; ++i) {
        points.emplace_back(double(i), 0, 0);
        weights.push_back(i < 10 ? 50.0 : 1.0);
    }
    const WorkBisection b = WorkBisection::balance(points, weights, 2);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(b.partOf(points[size_t(i)]), i < 6 ? 0 : 1) << i;
    const std::vector<double> w = partWeights(b, points, weights);
    EXPECT_EQ(w[0], 300.0);
    EXPECT_EQ(w[1], 290.0);
}

// More parts than points: 3 grains over 4 ranks leave one part empty and never two grains in
// one part; equal points stay together (no plane passes between them).
TEST(WorkBisection, MorePartsThanPointsLeavesPartsEmpty)
{
    const std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
    const WorkBisection b = WorkBisection::balance(points, {1.0, 1.0, 1.0}, 4);
    std::set<int> used;
    for (const Vec3& p : points) used.insert(b.partOf(p));
    EXPECT_EQ(used.size(), 3u);
    for (int p : used) EXPECT_TRUE(p >= 0 && p < 4);

    const std::vector<Vec3> same(6, Vec3(1, 2, 3));
    const WorkBisection c = WorkBisection::balance(same, std::vector<double>(6, 1.0), 3);
    for (const Vec3& p : same) EXPECT_EQ(c.partOf(p), c.partOf(same[0]));
    const WorkBisection none = WorkBisection::balance({}, {}, 3);
    EXPECT_EQ(none.parts(), 3);
}

// ---------------------------------------------------------------------------------------------
// Ranks as threads.
// ---------------------------------------------------------------------------------------------

namespace {

/// What the threads of one "job" share: a generation-counted barrier and each rank's bytes.
class ThreadJob
{
public:
    explicit ThreadJob(int ranks) : mRanks(ranks), mContributions(static_cast<size_t>(ranks)) {}
    int ranks() const { return mRanks; }

    void barrier()
    {
        std::unique_lock<std::mutex> lock(mMutex);
        const long long generation = mGeneration;
        if (++mArrived == mRanks) {
            mArrived = 0;
            ++mGeneration;
            mChanged.notify_all();
        } else {
            mChanged.wait(lock, [&] { return mGeneration != generation; });
        }
    }

    std::vector<char>& contribution(int rank) { return mContributions[size_t(rank)]; }
    std::vector<std::vector<char>>& outbox(int rank) { return mOutboxes[size_t(rank)]; }

private:
    int mRanks;
    std::mutex mMutex;
    std::condition_variable mChanged;
    int mArrived = 0;
    long long mGeneration = 0;
    std::vector<std::vector<char>> mContributions;
    std::vector<std::vector<std::vector<char>>> mOutboxes{size_t(mRanks)};
};

class ThreadRankGroup final : public RankGroup
{
public:
    ThreadRankGroup(ThreadJob& job, int rank) : mJob(job), mRank(rank) {}
    int rank() const override { return mRank; }
    int ranks() const override { return mJob.ranks(); }

    void allGather(const std::vector<char>& mine, std::vector<char>& all,
                   std::vector<size_t>& starts) override
    {
        mJob.contribution(mRank) = mine;
        mJob.barrier();  // every rank's bytes are in
        all.clear();
        starts.assign(1, 0);
        for (int r = 0; r < ranks(); ++r) {
            const std::vector<char>& c = mJob.contribution(r);
            all.insert(all.end(), c.begin(), c.end());
            starts.push_back(all.size());
        }
        mJob.barrier();  // every rank has read them before anyone writes again
    }

    void allToAll(const std::vector<std::vector<char>>& toEach, std::vector<char>& received,
                  std::vector<size_t>& starts) override
    {
        mJob.outbox(mRank) = toEach;
        mJob.barrier();  // every rank's bytes are in
        received.clear();
        starts.assign(1, 0);
        for (int r = 0; r < ranks(); ++r) {
            const std::vector<char>& c = mJob.outbox(r)[size_t(mRank)];
            received.insert(received.end(), c.begin(), c.end());
            starts.push_back(received.size());
        }
        mJob.barrier();  // every rank has read them before anyone writes again
    }

    bool anyRank(bool mine) override
    {
        std::vector<char> all;
        std::vector<size_t> starts;
        allGather(std::vector<char>(1, mine ? 1 : 0), all, starts);
        return std::find(all.begin(), all.end(), 1) != all.end();
    }

private:
    ThreadJob& mJob;
    int mRank;
};

/// A sphere of radius 2 with 300 nodes, baked once per program.
const std::string& sphereFile()
{
    static test::ScratchDir dir;
    static const std::string path = [] {
        BakeOptions o;
        o.voxelSize = 0.2;
        o.nodePlacement = NodePlacement::Count;
        o.nodeCount = 300;
        std::vector<std::string> warnings;
        const std::string file = dir.file("sphere.vdb");
        saveAsset(bakeAnalytic(AnalyticShape::sphere(2.0), o, warnings), file);
        return file;
    }();
    return path;
}

/// A box of a floor and four walls (x = ±11, y = ±9) with friction, under gravity, for spheres
/// of radius 2 (no grains yet).
/// The automatic step's safety for these scenes: steps long enough that the thrown spheres
/// cross the sub-domains within each test's steps (the stability check still watches them).
constexpr double kSafety = 0.45;

Scene sphereBox()
{
    Scene s;
    AssetSpec a;
    a.name = "sphere";
    a.file = sphereFile();
    s.assets.push_back(a);
    MaterialSpec rock;
    rock.name = "rock";
    rock.density = 2.65e-9;
    s.materials.push_back(rock);
    ContactSpec c;
    c.model.formulation = Formulation::Adapted;
    c.model.normalStiffness = 1e3;
    c.model.shearStiffness = 5e2;
    c.model.friction = 0.5;
    c.model.damping = ViscousDamping(0.5);
    s.contacts.push_back(c);
    const Vec3 normals[] = {Vec3::UnitZ(), Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(),
                            -Vec3::UnitY()};
    const Vec3 points[] = {Vec3::Zero(), Vec3(-11, 0, 0), Vec3(11, 0, 0), Vec3(0, -9, 0),
                           Vec3(0, 9, 0)};
    for (int k = 0; k < 5; ++k) {
        BoundarySpec b;
        b.name = "wall" + std::to_string(k);
        b.shape = BoundaryShape::Plane;
        b.point = points[k];
        b.normal = normals[k];
        s.boundaries.push_back(b);
    }
    s.gravity = Vec3(0, 0, -9810.0);
    return s;
}

/// @a count spheres (up to 4 × 3 × 3) dropped with random velocities and spins into the box:
/// within a few hundred steps they hit the walls, the floor and each other, and move across
/// the box (so across the sub-domains).
/// @a count spheres (up to 4 × 3 × 3) thrown into the box of @a s.
World throwSpheres(Scene s, int count)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < count; ++i) {
        GrainSpec g;
        g.pose.position = Vec3(-7.5 + 5.0 * (i % 4) + 0.2 * u(rng), -5.0 + 5.0 * ((i / 4) % 3),
                               2.05 + 5.0 * (i / 12));
        g.velocity = Vec3(1500.0 * u(rng), 1500.0 * u(rng), -500.0 + 300.0 * u(rng));
        g.angularVelocity = Vec3(50.0 * u(rng), 50.0 * u(rng), 50.0 * u(rng));
        s.grains.push_back(g);
    }
    std::vector<std::string> warnings;
    return buildWorld(s, warnings);
}

World droppedSpheres(int count)
{
    return throwSpheres(sphereBox(), count);
}

/// The thrown spheres with the wall at x = 11 a servo keeping a stress (it moves by the sum of
/// every grain's force on it), and one sphere prescribed to plough along +x with a spin (its
/// work is summed over the grains).
World servoAndPrescribed()
{
    Scene s = sphereBox();
    StressServo& servo = s.boundaries[2].servo;
    servo.targetStress = 1e-3;
    servo.area = 360.0;
    servo.maxSpeed = 300.0;
    World w = throwSpheres(s, 24);
    Grain& plough = w.grains[5];
    plough.motion = GrainMotion::Prescribed;
    plough.body.velocity = Vec3(800.0, 0.0, 0.0);
    plough.prescribedAngularVelocity = Vec3(0.0, 0.0, 40.0);
    return w;
}

/// Two spheres on the floor under a strong gravity, sliding along +x (friction 0.02: still
/// sliding at the end): the one from x = -8 crosses x = -2.5 (the cut between the two, drawn
/// by grain count) after about 1000 steps, in contact with the floor all along, so its floor
/// contact's shear history must travel with it to its new rank. (Rolling, a sphere of 299
/// nodes under this load rests on one or two of them, and hops from node to node like a
/// polyhedron: it could be in the air when it crosses.)
World slidingPair()
{
    Scene s = sphereBox();
    s.gravity = Vec3(0, 0, -2e6);
    s.contacts[0].model.friction = 0.02;
    for (double x : {-8.0, 3.0}) {
        GrainSpec g;
        g.pose.position = Vec3(x, 0.0, 1.999);
        g.velocity = Vec3(1500.0, 0.0, 0.0);
        s.grains.push_back(g);
    }
    std::vector<std::string> warnings;
    return buildWorld(s, warnings);
}


/// A 12 × 12 × 4 lattice of touching spheres (576, each pressing its neighbours by 0.02 mm) on
/// the floor: about 1700 contacts, more than a run of the one process's sums (512).
World touchingLattice()
{
    Scene s = sphereBox();
    s.boundaries.resize(1);  // the floor only
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j)
            for (int k = 0; k < 4; ++k) {
                GrainSpec g;
                g.pose.position = Vec3(-22.0 + 3.98 * i, -22.0 + 3.98 * j, 1.98 + 3.98 * k);
                s.grains.push_back(g);
            }
    std::vector<std::string> warnings;
    return buildWorld(s, warnings);
}

/// Everything of a world that must be the same on every rank, as bytes.
std::string stateBytes(const World& w, const Energies& energies, long long nodes,
                       const std::vector<ContactForceRecord>& forces)
{
    std::string out;
    auto put = [&](const void* p, size_t n) { out.append(static_cast<const char*>(p), n); };
    auto vec = [&](const Vec3& v) { put(v.data(), 3 * sizeof(double)); };
    auto history = [&](const ShearHistory& h) {
        for (const ShearHistory::Entry& e : h.entries()) {
            put(&e.node, sizeof e.node);
            vec(e.force);
            put(&e.stiffness, sizeof e.stiffness);
        }
        out += '|';
    };
    for (const Grain& g : w.grains) {
        vec(g.body.pose.position);
        put(g.body.pose.orientation.coeffs().data(), 4 * sizeof(double));
        vec(g.body.velocity);
        vec(g.body.angularMomentum);
        vec(g.force);
        vec(g.torque);
    }
    for (const Boundary& b : w.boundaries) vec(b.force);
    for (const auto& [key, h] : w.pairHistory) {
        put(&key, sizeof key);
        history(h.shearOnFirstNodes);
        history(h.shearOnSecondNodes);
    }
    for (const auto& [key, h] : w.boundaryHistory) {
        put(&key, sizeof key);
        history(h);
    }
    put(&energies, sizeof energies);
    put(&nodes, sizeof nodes);
    for (const ContactForceRecord& f : forces) {
        vec(f.point);
        vec(f.force);
        put(&f.grain, sizeof f.grain);
    }
    return out;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// Split by space: owned grains and ghosts (GhostDecomposition.h), on threads.
// ---------------------------------------------------------------------------------------------

namespace {

struct GhostOutcome
{
    std::string state;           ///< the whole world gathered from the ranks, as bytes (rank 0)
    GhostCounters counters;
    bool everOwned = false;      ///< owned some grain at some step
    int mostHeld = 0;            ///< most grains (owned + ghosts) held at once
};

/// Step @a world's scene on @a ranks thread-ranks split by space; one outcome per rank.
std::vector<GhostOutcome> runGhostsOnThreads(int ranks, World (*scene)(), int steps,
                                             double rebalanceAbove = 1.1,
                                             const World* restartFrom = nullptr)
{
    ThreadJob job(ranks);
    std::vector<GhostOutcome> outcomes(static_cast<size_t>(ranks));
    std::vector<std::thread> threads;
    for (int r = 0; r < ranks; ++r)
        threads.emplace_back([&, r] {
            ThreadRankGroup group(job, r);
            GhostDecomposition ghosts(group, rebalanceAbove);
            World world = restartFrom ? *restartFrom : scene();
            const double dt = automaticTimeStep(scene(), kSafety);
            Simulation sim(std::move(world), dt, !restartFrom, false, ghosts);
            GhostOutcome& o = outcomes[size_t(r)];
            for (int k = 0; k < steps; ++k) {
                sim.step();
                o.everOwned |= ghosts.counters().owned > 0;
                o.mostHeld = std::max(o.mostHeld, int(sim.world().grains.size()));
            }
            const World whole = ghosts.gatherWorld(sim.world());
            const Energies e = sim.energies();
            const long long nodes = sim.contactNodes();
            o.state = stateBytes(whole, e, nodes, {});
            o.counters = ghosts.counters();
        });
    for (std::thread& t : threads) t.join();
    return outcomes;
}

std::string serialState(World (*scene)(), int steps)
{
    World world = scene();
    const double dt = automaticTimeStep(world, kSafety);
    Simulation sim(std::move(world), dt, true, false);
    for (int k = 0; k < steps; ++k) sim.step();
    return stateBytes(sim.world(), sim.energies(), sim.contactNodes(), {});
}

World droppedSpheres24() { return droppedSpheres(24); }
World droppedSpheres3() { return droppedSpheres(3); }

} // namespace

// The 24 thrown spheres split by space on 1 to 4 thread-ranks: the world gathered from the
// ranks to rank 0 (every grain, force, boundary reaction, shear history, energy) is the single
// process's, byte for byte. The run is checked to test what it is meant to: every rank owns
// grains and holds ghosts, grains migrate with their contact histories, and ghost states travel.
TEST(GhostDecomposition, ThreadRanksEndBitIdenticalToOneProcess)
{
    const int steps = 1500;
    const std::string serial = serialState(droppedSpheres24, steps);
    for (int ranks : {1, 2, 3, 4}) {
        const std::vector<GhostOutcome> outcomes =
            runGhostsOnThreads(ranks, droppedSpheres24, steps);
        long long migrated = 0, histories = 0;
        for (int r = 0; r < ranks; ++r) {
            const GhostOutcome& o = outcomes[size_t(r)];
            if (r == 0) {
                EXPECT_TRUE(o.state == serial) << ranks << " ranks differ";
            }
            EXPECT_TRUE(o.everOwned) << ranks << " ranks: rank " << r;
            migrated += o.counters.grainsMigrated;
            histories += o.counters.historiesMigrated;
            if (ranks > 1) {
                EXPECT_GT(o.counters.bytesReceived, 0) << ranks << " ranks";
                EXPECT_GT(o.counters.ghostUpdates, 0) << ranks << " ranks";
            } else {
                EXPECT_EQ(o.counters.bytesReceived, 0);
                EXPECT_EQ(o.counters.ghosts, 0);
            }
        }
        std::cout << "[ measured ] " << ranks << " ranks: " << migrated << " grains and "
                  << histories << " shear histories migrated; ghosts at the end:";
        for (const GhostOutcome& o : outcomes) std::cout << " " << o.counters.ghosts;
        std::cout << "\n";
        if (ranks > 1) {
            EXPECT_GT(migrated, 0) << ranks << " ranks: no grain crossed";
            EXPECT_GT(histories, 0) << ranks << " ranks: no history travelled";
        }
    }
}

// 3 spheres on 4 ranks: some rank owns no grain; the gathered world is still the single
// process's, bit for bit.
TEST(GhostDecomposition, ARankWithoutGrains)
{
    const int steps = 400;
    const std::string serial = serialState(droppedSpheres3, steps);
    const std::vector<GhostOutcome> outcomes = runGhostsOnThreads(4, droppedSpheres3, steps);
    int idle = 0;
    EXPECT_TRUE(outcomes[0].state == serial);
    for (const GhostOutcome& o : outcomes) idle += o.counters.owned == 0;
    EXPECT_GE(idle, 1);
}

// A sphere sliding on the floor across the cut between two ranks (redraws off, so the cut
// stays): it migrates with the shear history of its floor contact, and the run ends as one
// process's, bit for bit. Without the history the friction on the new rank would restart
// from zero and the bytes would differ.
TEST(GhostDecomposition, AGrainCrossingCarriesItsShearHistory)
{
    const int steps = 1600;
    const std::string serial = serialState(slidingPair, steps);
    const std::vector<GhostOutcome> outcomes =
        runGhostsOnThreads(2, slidingPair, steps, 1e9);
    EXPECT_TRUE(outcomes[0].state == serial);
    EXPECT_EQ(outcomes[0].counters.rebalances, 1);  // the first draw only
    // Rank 1 (above the cut) received grain 0 and its floor history.
    EXPECT_EQ(outcomes[1].counters.grainsMigrated, 1);
    EXPECT_GE(outcomes[1].counters.historiesMigrated, 1);
    EXPECT_EQ(outcomes[1].counters.owned, 2);
    EXPECT_EQ(outcomes[0].counters.owned, 0);
}

// Above 512 contacts one process summed the elastic energy in runs of 512 and the ranks in one
// chain, so the last digits of energy.csv differed (issue 33, 1000 spheres). Now both sum the
// contacts in one chain in list order: the same bytes on 1, 2 and 3 ranks.
TEST(GhostDecomposition, ManyContactsSumTheSameOnAnyRankCount)
{
    const int steps = 5;
    const std::string serial = serialState(touchingLattice, steps);
    for (const int ranks : {2, 3}) {
        const std::vector<GhostOutcome> outcomes = runGhostsOnThreads(ranks, touchingLattice, steps);
        EXPECT_TRUE(outcomes[0].state == serial) << ranks << " ranks differ";
    }
}

// A restart split by space: the thrown spheres' world every 100 steps up to 1400 (grains,
// forces, shear histories: what a checkpoint holds) continued for 100 steps on 3 thread-ranks,
// against one process continuing from the same world. The first step after a restart moves
// the grains before any evaluation, so the ghosts must follow their owners even then (not
// doing so shows at the restart from step 800, whose spheres touch across a cut).
TEST(GhostDecomposition, ARestartContinuesAsOneProcess)
{
    World world = droppedSpheres24();
    const double dt = automaticTimeStep(world, kSafety);
    Simulation first(std::move(world), dt, true, false);
    for (int at = 100; at <= 1400; at += 100) {
        while (first.world().step < at) first.step();
        const World saved = first.world();
        Simulation serial(saved, dt, false, false);
        for (int k = 0; k < 100; ++k) serial.step();
        const std::string expected =
            stateBytes(serial.world(), serial.energies(), serial.contactNodes(), {});
        const std::vector<GhostOutcome> outcomes =
            runGhostsOnThreads(3, droppedSpheres24, 100, 1.1, &saved);
        EXPECT_TRUE(outcomes[0].state == expected) << "restarted at step " << at;
    }
}

// A servo wall and a prescribed grain on 3 thread-ranks: the wall's velocity comes from the
// sum of every grain's force on it, and the energy balance from the prescribed grain's work,
// both summed over the ranks in one process's order; the gathered world ends as one process's.
TEST(GhostDecomposition, AServoWallAndAPrescribedGrainSeeTheWholeSums)
{
    const int steps = 1200;
    World world = servoAndPrescribed();
    const double dt = automaticTimeStep(world, kSafety);
    Simulation serial(std::move(world), dt, true, false);
    for (int k = 0; k < steps; ++k) serial.step();
    // What the test relies on: the wall moved, and the prescribed grain did work.
    EXPECT_NE(serial.world().boundaries[2].displacement.x(), 0.0);
    EXPECT_NE(serial.world().energy.boundaryWork, 0.0);
    const std::string expected =
        stateBytes(serial.world(), serial.energies(), serial.contactNodes(), {});
    const std::vector<GhostOutcome> outcomes = runGhostsOnThreads(3, servoAndPrescribed, steps);
    EXPECT_TRUE(outcomes[0].state == expected);
}

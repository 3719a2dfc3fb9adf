// The contact backend seam (ContactBackend.h): a backend that visits the slots in another
// order, one at a time on one thread with its own working memory, gives the CPU backend's
// numbers bit for bit over a run with friction, damping, walls and shear histories. So a
// backend needs nothing but the batch, and the order of the slots does not matter.
#include "lsdem/simulation/ContactBackend.h"

#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/simulation/Simulation.h"

#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

using namespace lsdem;

namespace {

/// The slots last to first, each computed by computeContactSlot; counts how often it ran.
class ReverseSerialBackend final : public ContactBackend
{
public:
    explicit ReverseSerialBackend(int* calls) : mCalls(calls) {}
    std::unique_ptr<ContactBackend> clone() const override
    {
        return std::make_unique<ReverseSerialBackend>(mCalls);
    }
    void compute(const ContactBatch& batch) override
    {
        ++*mCalls;
        for (size_t k = batch.slots.size(); k-- > 0;) computeContactSlot(batch, k, mScratch);
    }

private:
    int* mCalls;
    ContactScratch mScratch;
};

/// Eight balls thrown into a box of walls under gravity, with friction and damping.
World tumblingBalls()
{
    std::ostringstream s;
    s << "[assets.ball]\nshape = \"sphere\"\nradius = 1.0\nvoxel = 0.1\nnodes = 400\n\n"
         "[materials.glass]\ndensity = 2.5e-9\n\n[[contacts]]\nmaterials = [\"glass\", \"glass\"]\n"
         "normal_stiffness = 1e3\nshear_stiffness = 5e2\nfriction = 0.4\nrestitution = 0.5\n\n";
    for (int i = 0; i < 8; ++i)
        s << "[[grains]]\nasset = \"ball\"\nmaterial = \"glass\"\nposition = ["
          << ((i & 1) ? 1.05 : -1.05) << ", " << ((i & 2) ? 1.05 : -1.05) << ", "
          << ((i & 4) ? 3.2 : 1.0) << "]\nvelocity = [" << 300.0 * ((i % 3) - 1) << ", "
          << 200.0 * ((i % 2) ? 1 : -1) << ", -100]\nangular_velocity = [0, " << 50 * i
          << ", 0]\n\n";
    const char* walls[][2] = {{"[0, 0, 0]", "[0, 0, 1]"},  {"[-2.5, 0, 0]", "[1, 0, 0]"},
                              {"[2.5, 0, 0]", "[-1, 0, 0]"}, {"[0, -2.5, 0]", "[0, 1, 0]"},
                              {"[0, 2.5, 0]", "[0, -1, 0]"}};
    for (int w = 0; w < 5; ++w)
        s << "[[boundaries]]\nname = \"w" << w << "\"\ntype = \"plane\"\nmaterial = \"glass\"\n"
          << "point = " << walls[w][0] << "\nnormal = " << walls[w][1] << "\n\n";
    s << "[simulation]\ngravity = [0, 0, -9810]\nend_steps = 1\n";
    std::vector<std::string> warnings;
    return buildWorld(parseScene(s.str(), "tumbling.toml"), warnings);
}

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }

} // namespace

TEST(ContactBackend, AnotherOrderOnOneThreadGivesTheSameBits)
{
    const double dt = 2e-6;
    Simulation cpu(tumblingBalls(), dt);
    Simulation other(tumblingBalls(), dt);
    int calls = 0;
    other.setContactBackend(std::make_unique<ReverseSerialBackend>(&calls));
    long long touching = 0;
    for (int step = 0; step < 400; ++step) {
        cpu.step();
        other.step();
        touching += cpu.contactNodes();
    }
    EXPECT_EQ(calls, 400);
    EXPECT_GT(touching, 0) << "the balls must meet the floor and each other";
    for (size_t i = 0; i < cpu.world().grains.size(); ++i) {
        const RigidBody& a = cpu.world().grains[i].body;
        const RigidBody& b = other.world().grains[i].body;
        EXPECT_TRUE(sameBits(a.pose.position, b.pose.position)) << i;
        EXPECT_TRUE(sameBits(a.velocity, b.velocity)) << i;
    }
    EXPECT_EQ(cpu.energies().elastic, other.energies().elastic);
    EXPECT_EQ(cpu.contactNodes(), other.contactNodes());
    // A copy of the simulation gets a backend of its own kind: it keeps calling the counter.
    Simulation copy = other;
    copy.step();
    EXPECT_EQ(calls, 401);
}

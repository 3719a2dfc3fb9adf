// The text outputs of a run: the history rows taken from a Simulation, energy.csv and
// boundary_<name>.csv written from them, and grains.csv; each read back here and compared
// exactly (17 significant digits read back to the same double), and boundary file names.
#include "lsdem/run/RunOutputs.h"

#include "lsdem/core/CsvText.h"
#include "lsdem/simulation/Micromechanics.h"

#include "support/TestSupport.h"
#include "support/TestAssets.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdlib>
#include <fstream>
#include <sstream>

using namespace lsdem;

namespace {

/// One free grain pressed ~0.014 into a floor (by one node) under gravity, a moving side wall
/// that does not touch it, and a second grain fixed far away; numbers with many digits.
World smallWorld()
{
    World w;
    w.materialCount = 1;
    ContactModel m;
    m.formulation = Formulation::Original;
    m.normalStiffness = 1000.0;
    w.models = {m};
    w.gravity = Vec3(0, 0, -9.81);
    const auto asset = std::make_shared<const GrainAsset>(lsdem::test::sixNodeAsset(2.0));
    Grain ball;
    ball.name = "ball";
    ball.asset = asset;
    ball.body.mass = 1.0 / 3.0;
    ball.body.principalInertia = Vec3(0.1, 0.2, 0.3);
    ball.body.pose.position = Vec3(0.1234567890123, -2.0 / 7.0, 0.97);
    ball.body.pose.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
    ball.body.velocity = Vec3(0.1, -0.2, 0.3);
    ball.body.setAngularVelocity(Vec3(0.01, 0.02, -0.03));
    w.grains.push_back(ball);
    Grain post = ball;
    post.name = "post";
    post.motion = GrainMotion::Fixed;
    post.body.pose.position = Vec3(50, 50, 50);
    post.body.velocity = Vec3::Zero();
    w.grains.push_back(post);
    Boundary floor;
    floor.name = "floor";
    w.boundaries.push_back(floor);
    Boundary wall;
    wall.name = "side wall/1.b";
    wall.plane.point = Vec3(-5, 0, 0);
    wall.plane.normal = Vec3::UnitX();
    wall.velocity = Vec3(0.25, 0, 0);
    w.boundaries.push_back(wall);
    return w;
}

std::string readFile(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The lines of a CSV file, each split at commas (no quoting in these files).
std::vector<std::vector<std::string>> readCsv(const std::string& path)
{
    return readCsvRecords(readFile(path), path);
}

double number(const std::string& text)
{
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    EXPECT_EQ(*end, '\0') << "not a number: '" << text << "'";
    return v;
}

/// The data rows of @a csv, which must have the header @a header, equal @a rows exactly.
void expectRowsReadBack(const std::string& csv, const std::string& header,
                        const std::vector<std::vector<double>>& rows)
{
    const auto lines = readCsv(csv);
    ASSERT_EQ(lines.size(), rows.size() + 1) << csv;
    std::string head;
    for (const std::string& f : lines[0]) head += (head.empty() ? "" : ",") + f;
    EXPECT_EQ(head, header);
    for (size_t r = 0; r < rows.size(); ++r) {
        ASSERT_EQ(lines[r + 1].size(), rows[r].size()) << csv << " row " << r;
        for (size_t c = 0; c < rows[r].size(); ++c)
            EXPECT_EQ(number(lines[r + 1][c]), rows[r][c]) << csv << " row " << r << " col " << c;
    }
}

} // namespace

TEST(RunOutputs, HistoryRowsAreTheSimulationsStateNow)
{
    Simulation sim(smallWorld(), 1e-4);
    RunRecord record;
    recordHistoryRow(sim, record);
    for (int k = 0; k < 5; ++k) sim.step();
    recordHistoryRow(sim, record);

    ASSERT_EQ(record.energyRows.size(), 2u);
    const Energies e = sim.energies();
    const std::vector<double> expected = {5.0, sim.world().time, e.kinetic, e.elastic,
                                          e.potential, e.boundaryWork, e.dissipated,
                                          static_cast<double>(sim.contactNodes()), e.friction,
                                          e.dashpot, e.globalDamping};
    EXPECT_EQ(record.energyRows[1], expected);
    EXPECT_EQ(record.energyRows[0][0], 0.0);
    EXPECT_EQ(record.energyRows[0][1], 0.0);
    EXPECT_EQ(record.energyRows[0][7], 1.0);  // the -z node is on the floor
    EXPECT_GT(record.energyRows[0][3], 0.0);  // so there is elastic energy

    ASSERT_EQ(record.boundaryRows.size(), 2u);
    for (size_t b = 0; b < 2; ++b) {
        ASSERT_EQ(record.boundaryRows[b].size(), 2u);
        const Boundary& bd = sim.world().boundaries[b];
        const std::vector<double> row = {5.0,  sim.world().time, bd.displacement.x(),
                                         bd.displacement.y(), bd.displacement.z(),
                                         bd.force.x(), bd.force.y(), bd.force.z()};
        EXPECT_EQ(record.boundaryRows[b][1], row);
    }
    // The floor holds the ball up (reaction down), the wall moved 5 steps at 0.25.
    EXPECT_LT(record.boundaryRows[0][1][7], 0.0);
    EXPECT_DOUBLE_EQ(record.boundaryRows[1][1][2], 5 * 1e-4 * 0.25);
}

// With record.micromechanics, each history row also takes Micromechanics.h's measures of the
// state then (the ball on the floor: one boundary contact, no grain contact, so the ball is a
// rattler and the stress moment is the floor contact's lever times its force); written to
// micromechanics.csv and read back exactly. Without it, no row and no file.
TEST(RunOutputs, MicromechanicsRowsAreTheSimulationsMeasuresNow)
{
    Simulation sim(smallWorld(), 1e-4);
    RunRecord plain, record;
    record.micromechanics = true;
    for (int k = 0; k < 3; ++k) sim.step();
    recordHistoryRow(sim, plain);
    recordHistoryRow(sim, record);
    EXPECT_TRUE(plain.micromechanicsRows.empty());
    ASSERT_EQ(record.micromechanicsRows.size(), 1u);
    const std::vector<ContactRecord> contacts = sim.contactRecords();
    const Micromechanics m = micromechanicsOf(sim.world(), contacts);
    std::vector<double> expected = {3.0, sim.world().time};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) expected.push_back(m.stressMoment(i, j));
    for (const Mat3* f : {&m.fabric, &m.branchFabric, &m.forceFabric})
        expected.insert(expected.end(), {(*f)(0, 0), (*f)(1, 1), (*f)(2, 2), (*f)(0, 1),
                                         (*f)(0, 2), (*f)(1, 2),
                                         f == &m.fabric         ? m.fabricAnisotropy
                                         : f == &m.branchFabric ? m.branchAnisotropy
                                                                : m.forceAnisotropy});
    expected.insert(expected.end(),
                    {m.meanNormalForce, double(m.grainContacts),
                     double(m.boundaryContacts), double(m.freeGrains), double(m.rattlers),
                     m.mechanicalCoordination});
    EXPECT_EQ(record.micromechanicsRows[0], expected);
    // The closed form of this state: the one floor contact's (x_c − x_p) ⊗ f.
    ASSERT_EQ(contacts.size(), 1u);
    const Vec3 lever = contacts[0].centre - sim.world().grains[0].body.pose.position;
    const Mat3 moment = lever * contacts[0].force.transpose();
    EXPECT_LT((m.stressMoment - moment).norm(), 1e-12 * moment.norm());
    EXPECT_EQ(m.boundaryContacts, 1);
    EXPECT_EQ(m.grainContacts, 0);
    EXPECT_EQ(m.rattlers, 1);

    lsdem::test::ScratchDir dir;
    writeHistoryFiles(dir.path().string(), sim.world(), plain);
    EXPECT_FALSE(std::filesystem::exists(dir.file(kMicromechanicsFileName)));
    writeHistoryFiles(dir.path().string(), sim.world(), record);
    const std::string header =
        "step,time,mxx,mxy,mxz,myx,myy,myz,mzx,mzy,mzz,fxx,fyy,fzz,fxy,fxz,fyz,"
        "fabric_anisotropy,bxx,byy,bzz,bxy,bxz,byz,branch_anisotropy,nxx,nyy,nzz,nxy,nxz,nyz,"
        "force_anisotropy,mean_normal_force,grain_contacts,boundary_contacts,free_grains,"
        "rattlers,mechanical_coordination";
    expectRowsReadBack(dir.file(kMicromechanicsFileName), header, record.micromechanicsRows);
    EXPECT_TRUE(isRunTextOutput(dir.file(kMicromechanicsFileName)));
}

TEST(RunOutputs, HistoryFilesReadBackExactly)
{
    test::ScratchDir dir;
    Simulation sim(smallWorld(), 1e-4);
    RunRecord record;
    for (int k = 0; k < 3; ++k) {
        recordHistoryRow(sim, record);
        sim.step();
    }
    writeHistoryFiles(dir.path().string(), sim.world(), record);
    expectRowsReadBack(dir.file("energy.csv"),
                       "step,time,kinetic,elastic,potential,boundary_work,dissipated,"
                       "contact_nodes,dissipated_friction,dissipated_dashpot,"
                       "dissipated_global_damping",
                       record.energyRows);
    expectRowsReadBack(dir.file("boundary_floor.csv"), "step,time,ux,uy,uz,fx,fy,fz",
                       record.boundaryRows[0]);
    expectRowsReadBack(dir.file("boundary_side_wall_1_b.csv"), "step,time,ux,uy,uz,fx,fy,fz",
                       record.boundaryRows[1]);
    EXPECT_EQ(dir.entryCount(), 3u);  // no temporaries left behind

    // Written again with more rows: the files are replaced whole.
    recordHistoryRow(sim, record);
    writeHistoryFiles(dir.path().string(), sim.world(), record);
    EXPECT_EQ(readCsv(dir.file("energy.csv")).size(), 5u);
    EXPECT_EQ(dir.entryCount(), 3u);
}

TEST(RunOutputs, GrainsFileHoldsEachGrainsFinalStateExactly)
{
    test::ScratchDir dir;
    World w = smallWorld();
    const std::vector<Vec3> initial = {Vec3(0.1, 0.2, 0.3), w.grains[1].body.pose.position};
    w.grains[1].motion = GrainMotion::Prescribed;
    w.grains[1].body.velocity = Vec3(1.0 / 3.0, 0, 0);
    w.grains[1].prescribedAngularVelocity = Vec3(0, 0, 2.0 / 3.0);
    writeGrainsFile(dir.file("grains.csv"), w, initial);

    const auto lines = readCsv(dir.file("grains.csv"));
    ASSERT_EQ(lines.size(), 3u);
    std::string head;
    for (const std::string& f : lines[0]) head += (head.empty() ? "" : ",") + f;
    EXPECT_EQ(head, "name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,moved");
    for (size_t i = 0; i < 2; ++i) {
        const Grain& g = w.grains[i];
        const auto& f = lines[i + 1];
        ASSERT_EQ(f.size(), 15u);
        EXPECT_EQ(f[0], g.name);
        const RigidPose& p = g.body.pose;
        const Vec3 omega = g.angularVelocity();
        const double values[] = {p.position.x(),      p.position.y(),      p.position.z(),
                                 p.orientation.w(),   p.orientation.x(),   p.orientation.y(),
                                 p.orientation.z(),   g.body.velocity.x(), g.body.velocity.y(),
                                 g.body.velocity.z(), omega.x(),           omega.y(),
                                 omega.z(),           (p.position - initial[i]).norm()};
        for (size_t c = 0; c < 14; ++c) EXPECT_EQ(number(f[c + 1]), values[c]) << i << " " << c;
    }
    EXPECT_EQ(number(lines[2][15 - 1]), 0.0);  // the post has not moved
    EXPECT_EQ(number(lines[2][13]), 2.0 / 3.0);  // its prescribed spin, not its momentum's
}

TEST(RunOutputs, BoundaryFileNamesReplaceUnsafeCharacters)
{
    EXPECT_EQ(boundaryHistoryFileName("top"), "boundary_top.csv");
    EXPECT_EQ(boundaryHistoryFileName("Top-wall_2"), "boundary_Top-wall_2.csv");
    EXPECT_EQ(boundaryHistoryFileName("top wall/1.b"), "boundary_top_wall_1_b.csv");
    EXPECT_EQ(boundaryHistoryFileName("../x"), "boundary____x.csv");  // never leaves the folder
    // Each byte of a non-ASCII character is replaced (é is two bytes in UTF-8).
    EXPECT_EQ(boundaryHistoryFileName("caf\xc3\xa9"), "boundary_caf__.csv");
}

// The scene reader accepts any grain name, so grains.csv quotes a name with a comma (RFC 4180)
// and it keeps its column: 15 fields under the 15-column header, the name read back whole.
TEST(RunOutputs, GrainNameWithACommaStaysInItsColumn)
{
    test::ScratchDir dir;
    World w = smallWorld();
    w.grains[0].name = "left,top \"A\"";
    writeGrainsFile(dir.file("grains.csv"), w, {Vec3::Zero(), Vec3::Zero()});
    const auto lines = readCsv(dir.file("grains.csv"));
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[1].size(), 15u) << readFile(dir.file("grains.csv"));
    EXPECT_EQ(lines[1][0], "left,top \"A\"");
}

// A grain with an empty name (possible through the World API; buildWorld names them) keeps its
// (empty) name column: 15 fields under the 15-column header.
TEST(RunOutputs, EmptyGrainNameKeepsItsColumn)
{
    test::ScratchDir dir;
    World w = smallWorld();
    w.grains[0].name = "";
    writeGrainsFile(dir.file("grains.csv"), w, {Vec3::Zero(), Vec3::Zero()});
    const auto lines = readCsv(dir.file("grains.csv"));
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[1].size(), 15u) << readFile(dir.file("grains.csv"));
}

// The reference-force data: assets, recomputation, and the text format of the files (see
// ReferenceForces.h). The cases themselves and their plausibility checks are in
// ReferenceForceCases.cpp.
#include "libcontact/contact/ReferenceForces.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/LevelSetSampler.h"

#include "support/TestMeshes.h"
#include "support/TestSupport.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace lsdem::test::reference {

const std::vector<std::string>& kindNames()
{
    static const std::vector<std::string> names = {
        "grain-grain-one-way", "grain-grain-symmetric", "grain-plane",
        "grain-patch",         "grain-sphere",          "grain-level-set"};
    return names;
}

bool isGrainPair(const Case& c) { return c.kind.rfind("grain-grain", 0) == 0; }

// ---- Assets ------------------------------------------------------------------------------

namespace {

/// A unit sphere: its exact distance (voxels of 0.1 for the culling bounds); the nodes the
/// 642 vertices of an icosahedron subdivided three times (built in TestMeshes.h, not by the
/// remesher, so they depend on nothing but arithmetic), with mesh areas and exact normals.
GrainAsset bakeSphere()
{
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodeSpacing = 0.5;  // the baked nodes are replaced below
    o.exteriorBandVoxels = 3;
    std::vector<std::string> warnings;
    GrainAsset a = bakeAnalytic(AnalyticShape::sphere(1.0), o, warnings);
    a.nodes = nodesFromMesh(makeIcosphere(3), AreaRule::Mesh);
    for (size_t i = 0; i < a.nodes.size(); ++i)
        a.nodes.normals[i] = a.nodes.positions[i].normalized();
    sortNodesSpatially(a.nodes, 8 * o.voxelSize);
    a.nodeBlocks = groupNodesIntoBlocks(a.nodes);
    a.spacing = nodeSpacing(a.nodes);
    a.boundingRadius = 0.0;
    for (const Vec3& p : a.nodes.positions) a.boundingRadius = std::max(a.boundingRadius, p.norm());
    return withExactDistance(a, AnalyticShape::sphere(1.0).exactDistance());
}

/// A 2 × 1.6 × 1.2 box: its exact distance (voxels of 0.1 for the culling bounds), structured
/// face grids of spacing 0.2 (the bake of a box uses no remesher).
GrainAsset bakeBox()
{
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodeSpacing = 0.2;
    o.exteriorBandVoxels = 3;
    std::vector<std::string> warnings;
    const AnalyticShape box = AnalyticShape::box(2.0, 1.6, 1.2);
    return withExactDistance(bakeAnalytic(box, o, warnings), box.exactDistance());
}

} // namespace

const GrainAsset& referenceAsset(const std::string& name)
{
    static const GrainAsset sphere = bakeSphere();
    static const GrainAsset box = bakeBox();
    if (name == "sphere") return sphere;
    if (name == "box") return box;
    throw std::runtime_error("unknown reference asset '" + name + "'");
}

std::vector<std::string> assetRecipes()
{
    const GrainAsset& s = referenceAsset("sphere");
    const GrainAsset& b = referenceAsset("box");
    return {"(each level set sampled as its shape's exact distance, ExactDistance.h: no voxel",
            " values enter the forces; voxels of 0.1, band 3, only bound where phi < 0 can be)",
            "sphere: radius 1; bakeAnalytic(sphere(1)) at voxel 0.1, band 3 voxels;",
            "  nodes: the " + std::to_string(s.nodes.size()) +
                " vertices of an icosahedron subdivided 3 times (tests/support/TestMeshes.h),",
            "  mesh areas, exact normals, Morton-sorted in cells of 0.8, grouped for culling",
            "box: 2 x 1.6 x 1.2; bakeAnalytic(box) at voxel 0.1, node spacing 0.2, band 3",
            "  voxels (" + std::to_string(b.nodes.size()) + " nodes)"};
}

// ---- Recomputation -----------------------------------------------------------------------

namespace {

ContactGrain grainView(const std::string& asset, const BodyState& s, double mass, int index)
{
    ContactGrain g;
    g.asset = &referenceAsset(asset);
    g.pose = s.pose;
    g.velocity = s.velocity;
    g.angularVelocity = s.angularVelocity;
    g.index = index;
    g.mass = mass;
    return g;
}

Boundary movedBoundary(const Case& c, const Evaluation& e)
{
    Boundary b = c.boundary;
    b.velocity = e.boundaryVelocity;
    b.displacement = e.boundaryDisplacement;
    return b;
}

} // namespace

std::vector<Outcome> evaluate(const Case& c)
{
    PairHistory pairHistory;
    ShearHistory boundaryHistory;
    std::vector<Outcome> outcomes;
    for (const Evaluation& e : c.evaluations) {
        const ContactGrain first = grainView(c.firstAsset, e.first, c.firstMass, 0);
        NodeCheckStats stats;
        PairForces r;
        if (isGrainPair(c)) {
            const ContactGrain second = grainView(c.secondAsset, e.second, c.secondMass, 1);
            r = computePairContact(first, second, c.model, e.dt, &pairHistory, stats);
        } else {
            // As Simulation::evaluateForces: the boundary is an immovable body at its reference
            // point, moving at its velocity; the grain's nodes are tested against it.
            const Boundary b = movedBoundary(c, e);
            ContactGrain other;
            other.asset = b.asset.get();
            other.pose.position = b.referencePoint();
            other.pose.orientation = b.pose.orientation;
            other.velocity = b.velocity;
            ContactSide side;
            side.tester = &first;
            side.other = &other;
            side.history = &boundaryHistory;
            findBoundaryContacts(*first.asset, first.pose, b, side.contacts, stats);
            r = resolveContact(&side, 1, c.model, e.dt, nullptr);
        }
        Outcome o;
        o.nodes = r.contactNodes;
        o.forceFirst = r.forceOnFirst;
        o.torqueFirst = r.torqueOnFirst;
        o.forceSecond = r.forceOnSecond;
        o.torqueSecond = r.torqueOnSecond;
        o.elasticEnergy = r.elasticEnergy;
        outcomes.push_back(o);
    }
    return outcomes;
}

namespace {

double levelSetMargin(const GrainAsset& a, const RigidPose& poseA, const GrainAsset& b,
                      const RigidPose& poseB)
{
    LevelSetSampler sampler(*b.levelSet);
    double margin = std::numeric_limits<double>::infinity();
    for (const Vec3& p : a.nodes.positions)
        margin = std::min(margin, std::abs(sampler.phi(poseB.toLocal(poseA.toWorld(p)))));
    return margin;
}

} // namespace

double contactMargin(const Case& c, const Evaluation& e)
{
    const GrainAsset& a = referenceAsset(c.firstAsset);
    const RigidPose& pose = e.first.pose;
    if (isGrainPair(c)) {
        const GrainAsset& b = referenceAsset(c.secondAsset);
        return std::min(levelSetMargin(a, pose, b, e.second.pose),
                        levelSetMargin(b, e.second.pose, a, pose));
    }
    const Boundary bd = movedBoundary(c, e);
    if (bd.shape == BoundaryShape::LevelSet) {
        RigidPose obstacle = bd.pose;
        obstacle.position += bd.displacement;
        return levelSetMargin(a, pose, *bd.asset, obstacle);
    }
    double margin = std::numeric_limits<double>::infinity();
    for (const Vec3& p : a.nodes.positions) {
        const Vec3 x = pose.toWorld(p);
        if (bd.shape == BoundaryShape::Sphere) {
            margin = std::min(margin, std::abs((x - bd.referencePoint()).norm() - bd.radius));
            continue;
        }
        Plane plane = bd.plane;
        plane.point += bd.displacement;
        const double d = plane.signedDistance(x);
        margin = std::min(margin, std::abs(d));
        if (d >= 0.0) continue;
        // Behind the plane, a patch's edges and thickness decide too.
        const Vec3 offset = x - plane.point;
        const Vec3 axisV = plane.normal.cross(plane.axisU);
        const std::pair<double, double> edges[] = {
            {std::abs(offset.dot(plane.axisU)), plane.halfU},
            {std::abs(offset.dot(axisV)), plane.halfV},
            {-d, plane.thickness}};
        for (const auto& [value, limit] : edges)
            if (std::isfinite(limit)) margin = std::min(margin, std::abs(value - limit));
    }
    return margin;
}

// ---- The file format ---------------------------------------------------------------------

std::string referenceFilePath(Formulation f)
{
    return std::string(LSDEM_SOURCE_DIR) + "/tests/data/reference_forces/" +
           formulationName(f) + ".txt";
}

namespace {

std::string number(double v)
{
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);  // reads back to the same double
    return buffer;
}

std::string vec(const Vec3& v) { return number(v.x()) + " " + number(v.y()) + " " + number(v.z()); }

std::string quat(const Quat& q)
{
    return number(q.w()) + " " + number(q.x()) + " " + number(q.y()) + " " + number(q.z());
}

std::string today()
{
    const std::time_t now = std::time(nullptr);
    char buffer[16];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%d", std::gmtime(&now));
    return buffer;
}

/// The commit the files are generated from (regeneration insists that nothing but the files
/// themselves differs from it: uncommittedChanges).
std::string gitVersion()
{
    const CommandResult r =
        runCommand("git -C '" + std::string(LSDEM_SOURCE_DIR) + "' rev-parse --short HEAD");
    std::string text = r.exitCode == 0 ? r.output : "unknown";
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    return text;
}

void writeBody(std::ostream& out, const std::string& prefix, const BodyState& s)
{
    out << prefix << "_position " << vec(s.pose.position) << "\n"
        << prefix << "_orientation " << quat(s.pose.orientation) << "\n"
        << prefix << "_velocity " << vec(s.velocity) << "\n"
        << prefix << "_angular_velocity " << vec(s.angularVelocity) << "\n";
}

void writeBoundary(std::ostream& out, const Case& c)
{
    const Boundary& b = c.boundary;
    switch (b.shape) {
    case BoundaryShape::Plane:
        out << "boundary plane\n"
            << "plane_point " << vec(b.plane.point) << "\n"
            << "plane_normal " << vec(b.plane.normal) << "\n"
            << "plane_axis_u " << vec(b.plane.axisU) << "\n"
            << "plane_half_u " << number(b.plane.halfU) << "\n"
            << "plane_half_v " << number(b.plane.halfV) << "\n"
            << "plane_thickness " << number(b.plane.thickness) << "\n";
        return;
    case BoundaryShape::Sphere:
        out << "boundary sphere\n"
            << "sphere_center " << vec(b.center) << "\n"
            << "sphere_radius " << number(b.radius) << "\n";
        return;
    case BoundaryShape::LevelSet:
        out << "boundary level-set " << c.secondAsset << "\n"
            << "obstacle_position " << vec(b.pose.position) << "\n"
            << "obstacle_orientation " << quat(b.pose.orientation) << "\n";
        return;
    case BoundaryShape::Cylinder:  // no reference case uses one
    case BoundaryShape::Orifice:
        throw std::logic_error("reference forces: no file format for a cylinder or orifice boundary");
    }
}

} // namespace

std::string uncommittedChanges()
{
    // The reference files are left out: regenerating the first changes it before the next
    // formulation's turn.
    const CommandResult r = runCommand("git -C '" + std::string(LSDEM_SOURCE_DIR) +
                                       "' status --porcelain --untracked-files=no -- . "
                                       "':!tests/data/reference_forces'");
    if (r.exitCode != 0) return "(git status failed: not a git checkout?)";
    return r.output;
}

void writeReferenceFile(const std::string& path, Formulation f, const std::vector<Case>& cases,
                        const std::vector<std::string>& checks)
{
    std::ostringstream out;
    const GrainAsset& sphere = referenceAsset("sphere");
    out << "# lsdem reference forces: formulation \"" << formulationName(f) << "\"\n"
        << "#\n"
        << "# Generated " << today() << " by lsdem " << sphere.provenance.lsdemVersion << " (git "
        << gitVersion() << ") with\n"
        << "#   LSDEM_REGENERATE_REFERENCE=1 build/tests/test_contact "
           "--gtest_filter='*ReferenceForces*'\n"
        << "# from tests/libcontact/contact/ReferenceForceCases.cpp. Regenerate only for an\n"
        << "# intended change of the contact laws, and say why in the commit.\n"
        << "#\n"
        << "# Each case: two bodies in contact, the model (normal stiffness, shear stiffness,\n"
        << "# friction, restitution; units consistent, e.g. mm, N, s, t) and two evaluations,\n"
        << "# the second one step dt later (the bodies moved at their velocities) with the shear\n"
        << "# history of the first. Expected: penetrating nodes; force and torque on the first\n"
        << "# grain and on the second body (a boundary's torque is about its reference point);\n"
        << "# elastic energy. TestReferenceForces.cpp recomputes each evaluation and compares\n"
        << "# to 1e-12 of the force scale (the computation is deterministic; the tolerance only\n"
        << "# absorbs compiler and FMA rounding).\n"
        << "#\n"
        << "# Assets (baked by the test with fixed options):\n";
    for (const std::string& line : assetRecipes()) out << "#   " << line << "\n";
    out << "#\n# Checked when generated:\n";
    for (const std::string& line : checks) out << "#   " << line << "\n";
    out << "\nformulation " << formulationName(f) << "\n";
    for (const Case& c : cases) {
        out << "\ncase " << c.kind << "\n"
            << "testing " << nodeTestingName(c.model.testing) << "\n"
            << "model " << number(c.model.normalStiffness) << " "
            << number(c.model.shearStiffness) << " " << number(c.model.friction) << " "
            << number(c.model.damping.restitution()) << "\n"
            << "first " << c.firstAsset << " " << number(c.firstMass) << "\n";
        if (isGrainPair(c))
            out << "second " << c.secondAsset << " " << number(c.secondMass) << "\n";
        else
            writeBoundary(out, c);
        for (size_t k = 0; k < c.evaluations.size(); ++k) {
            const Evaluation& e = c.evaluations[k];
            const Outcome& o = c.expected[k];
            out << "\neval " << k + 1 << "\n"
                << "# margin " << number(contactMargin(c, e))
                << " (no node closer to a surface or patch edge)\n"
                << "dt " << number(e.dt) << "\n";
            writeBody(out, "first", e.first);
            if (isGrainPair(c)) {
                writeBody(out, "second", e.second);
            } else {
                out << "boundary_velocity " << vec(e.boundaryVelocity) << "\n"
                    << "boundary_displacement " << vec(e.boundaryDisplacement) << "\n";
            }
            out << "nodes " << o.nodes << "\n"
                << "force_first " << vec(o.forceFirst) << "\n"
                << "torque_first " << vec(o.torqueFirst) << "\n"
                << "force_second " << vec(o.forceSecond) << "\n"
                << "torque_second " << vec(o.torqueSecond) << "\n"
                << "elastic_energy " << number(o.elasticEnergy) << "\n";
        }
    }
    writeTextFileAtomically(path, out.str());
}

namespace {

/// The key → words of one block ("case" or "eval"), with the line of each key for messages.
struct Block
{
    std::map<std::string, std::vector<std::string>> values;
    std::map<std::string, int> lines;
    std::string path;

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const
    {
        const auto line = lines.find(key);
        const std::string where =
            line == lines.end() ? std::string("?") : std::to_string(line->second);
        throw std::runtime_error(path + ":" + where + ": " + key + ": " + problem);
    }
    const std::vector<std::string>& words(const std::string& key, size_t count) const
    {
        const auto found = values.find(key);
        if (found == values.end()) fail(key, "missing");
        if (found->second.size() != count)
            fail(key, "expected " + std::to_string(count) + " values");
        return found->second;
    }
    double number(const std::string& key, size_t index = 0, size_t count = 1) const
    {
        const std::string& text = words(key, count)[index];
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0') fail(key, "'" + text + "' is not a number");
        return v;
    }
    Vec3 vec(const std::string& key) const
    {
        return Vec3(number(key, 0, 3), number(key, 1, 3), number(key, 2, 3));
    }
    Quat quat(const std::string& key) const
    {
        return Quat(number(key, 0, 4), number(key, 1, 4), number(key, 2, 4), number(key, 3, 4));
    }
    BodyState body(const std::string& prefix) const
    {
        BodyState s;
        s.pose.position = vec(prefix + "_position");
        s.pose.orientation = quat(prefix + "_orientation");
        s.velocity = vec(prefix + "_velocity");
        s.angularVelocity = vec(prefix + "_angular_velocity");
        return s;
    }
};

Case caseFromBlock(const Block& b)
{
    Case c;
    c.kind = b.words("case", 1)[0];
    c.model.testing = parseNodeTesting(b.words("testing", 1)[0]);
    c.model.normalStiffness = b.number("model", 0, 4);
    c.model.shearStiffness = b.number("model", 1, 4);
    c.model.friction = b.number("model", 2, 4);
    c.model.damping = ViscousDamping(b.number("model", 3, 4));
    c.firstAsset = b.words("first", 2)[0];
    c.firstMass = b.number("first", 1, 2);
    if (isGrainPair(c)) {
        c.secondAsset = b.words("second", 2)[0];
        c.secondMass = b.number("second", 1, 2);
        return c;
    }
    const auto found = b.values.find("boundary");
    if (found == b.values.end() || found->second.empty()) b.fail("boundary", "missing");
    const std::string& shape = found->second[0];
    if (shape == "plane") {
        c.boundary.shape = BoundaryShape::Plane;
        c.boundary.plane.point = b.vec("plane_point");
        c.boundary.plane.normal = b.vec("plane_normal");
        c.boundary.plane.axisU = b.vec("plane_axis_u");
        c.boundary.plane.halfU = b.number("plane_half_u");
        c.boundary.plane.halfV = b.number("plane_half_v");
        c.boundary.plane.thickness = b.number("plane_thickness");
    } else if (shape == "sphere") {
        c.boundary.shape = BoundaryShape::Sphere;
        c.boundary.center = b.vec("sphere_center");
        c.boundary.radius = b.number("sphere_radius");
    } else if (shape == "level-set") {
        c.secondAsset = b.words("boundary", 2)[1];
        c.boundary.shape = BoundaryShape::LevelSet;
        c.boundary.asset = std::shared_ptr<const GrainAsset>(&referenceAsset(c.secondAsset),
                                                             [](const GrainAsset*) {});
        c.boundary.pose.position = b.vec("obstacle_position");
        c.boundary.pose.orientation = b.quat("obstacle_orientation");
    } else {
        b.fail("boundary", "unknown shape '" + shape + "'");
    }
    return c;
}

void addEvaluation(Case& c, const Block& b)
{
    Evaluation e;
    e.dt = b.number("dt");
    e.first = b.body("first");
    if (isGrainPair(c)) {
        e.second = b.body("second");
    } else {
        e.boundaryVelocity = b.vec("boundary_velocity");
        e.boundaryDisplacement = b.vec("boundary_displacement");
    }
    Outcome o;
    o.nodes = static_cast<int>(b.number("nodes"));
    o.forceFirst = b.vec("force_first");
    o.torqueFirst = b.vec("torque_first");
    o.forceSecond = b.vec("force_second");
    o.torqueSecond = b.vec("torque_second");
    o.elasticEnergy = b.number("elastic_energy");
    c.evaluations.push_back(e);
    c.expected.push_back(o);
}

} // namespace

std::vector<Case> readReferenceFile(const std::string& path, Formulation& formulation)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::vector<Case> cases;
    std::vector<Block> blocks;  // a case block, then its eval blocks, ...
    std::vector<bool> isCase;
    bool haveFormulation = false;
    std::string line;
    for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
        const size_t hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        std::istringstream words(line);
        std::string key, word;
        if (!(words >> key)) continue;
        std::vector<std::string> values;
        while (words >> word) values.push_back(word);
        if (key == "formulation") {
            if (values.size() != 1)
                throw std::runtime_error(path + ":" + std::to_string(lineNumber) +
                                         ": formulation wants one name");
            formulation = parseFormulation(values[0]);
            haveFormulation = true;
            continue;
        }
        if (key == "case" || key == "eval") {
            blocks.emplace_back();
            blocks.back().path = path;
            isCase.push_back(key == "case");
        }
        if (blocks.empty())
            throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": '" + key +
                                     "' before any case");
        blocks.back().values[key] = values;
        blocks.back().lines[key] = lineNumber;
    }
    if (!haveFormulation) throw std::runtime_error(path + ": no formulation line");
    for (size_t k = 0; k < blocks.size(); ++k) {
        if (isCase[k]) {
            cases.push_back(caseFromBlock(blocks[k]));
            cases.back().model.formulation = formulation;
        } else {
            if (cases.empty()) throw std::runtime_error(path + ": an eval before any case");
            addEvaluation(cases.back(), blocks[k]);
        }
    }
    return cases;
}

} // namespace lsdem::test::reference

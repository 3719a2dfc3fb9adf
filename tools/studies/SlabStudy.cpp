#include "studies/SlabStudy.h"

#include "studies/FormulationList.h"

#include "lsdem/ls/Stopwatch.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/simulation/World.h"
#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/AtomicFile.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/Error.h"
#include "lsdem/ls/MeshIO.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>
#include <thread>

namespace lsdem {

namespace {

std::string show(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

bool perArea(Formulation f) { return normalModel(f).stiffnessPerArea(); }


std::vector<double> snapshotDeltasOf(const SlabStudyOptions& o)
{
    if (!o.snapshotDeltas.empty()) {
        std::vector<double> d = o.snapshotDeltas;
        std::sort(d.begin(), d.end());
        return d;
    }
    std::vector<double> d;
    for (int k = 0; k <= 5; ++k) d.push_back(slabDeltaMax(o) * k / 5.0);
    return d;
}

/// Sorted coarse to fine, duplicates dropped.
std::vector<double> coarseToFine(std::vector<double> v)
{
    std::sort(v.begin(), v.end(), std::greater<double>());
    v.erase(std::unique(v.begin(), v.end(), [](double a, double b) {
                return std::abs(a - b) <= 1e-12 * std::max(a, b);
            }),
            v.end());
    return v;
}

/// Nodes on a block surface of area @a area remeshed at edge length @a sdp (equilateral
/// triangles, two per vertex).
double nodesForSpacing(double area, double sdp) { return 2.0 * area / (std::sqrt(3.0) * sdp * sdp); }

double blockSurfaceArea(const SlabPanel& panel) { return surfaceArea(panel.referenceMesh()); }

/// Whether stage 1 runs formulation @a f at node spacing @a sdp: the per-node formulations
/// (original, single-node) only at o.originalSdps when given (their time step shrinks with the
/// node count, so their finest runs cost the most).
bool runsAt(const SlabStudyOptions& o, Formulation f, double sdp)
{
    if (perArea(f) || o.originalSdps.empty()) return true;
    for (double s : o.originalSdps)
        if (std::abs(s - sdp) <= 1e-12 * sdp) return true;
    return false;
}

} // namespace

double slabDeltaMax(const SlabStudyOptions& o)
{
    // Twice the thickness: the central block is out well before (at about 1.6 t by default).
    return o.deltaMax > 0.0 ? o.deltaMax : 2.0 * o.panel.thickness;
}

void checkSlabStudyOptions(const SlabStudyOptions& o)
{
    checkSlabPanelOptions(o.panel);
    auto positive = [](double v, const std::string& option, const std::string& example) {
        if (!(v > 0.0) || !std::isfinite(v))
            throw Error("", option + " must be positive and finite, got " + show(v),
                        "e.g. " + option + " " + example);
    };
    auto nonNegative = [](double v, const std::string& option) {
        if (!(v >= 0.0) || !std::isfinite(v))
            throw Error("", option + " must be zero (default) or positive, got " + show(v));
    };
    const SlabMaterial& m = o.material;
    positive(m.youngModulus, "--young", "7e4");
    if (!(m.poisson >= 0.0 && m.poisson < 0.5))
        throw Error("", "--poisson must be in [0, 0.5), got " + show(m.poisson), "e.g. --poisson 0.22");
    positive(m.density, "--density", "2.5e-9");
    nonNegative(m.friction, "--friction");
    if (!(m.restitution > 0.0 && m.restitution <= 1.0))
        throw Error("", "--restitution must be in (0, 1], got " + show(m.restitution),
                    "1 means no contact damping");
    if (!(m.globalDamping >= 0.0 && m.globalDamping < 1.0))
        throw Error("", "--damping must be in [0, 1), got " + show(m.globalDamping));
    nonNegative(m.gravity, "--gravity");
    nonNegative(o.knStar, "--kn-star");
    nonNegative(o.ksStar, "--ks-star");
    nonNegative(o.knOriginal, "--kn");
    nonNegative(o.referenceSdp, "--reference-sdp");
    positive(o.indenterRadius, "--indenter-radius", "2.5");
    positive(o.speed, "--speed", "200");
    nonNegative(o.deltaMax, "--delta-max");
    if (slabDeltaMax(o) > 3.0 * o.panel.thickness)
        throw Error("", "--delta-max " + show(slabDeltaMax(o)) + " is more than three block thicknesses",
                    "the central block is out long before; e.g. --delta-max " + show(o.panel.thickness));
    // The step is set from the normal stiffness of a face; shear and rocking make a block
    // stiffer than that by up to about 1.4x (ks*/kn* = 0.41 by default), hence the cap.
    if (!(o.timeStepSafety > 0.0 && o.timeStepSafety <= 0.5))
        throw Error("", "--safety must be in (0, 0.5], got " + show(o.timeStepSafety), "0.3 is the default");
    checkFormulationList(o.formulations);
    if (o.twoWay && std::find(o.formulations.begin(), o.formulations.end(), Formulation::Adapted) ==
                        o.formulations.end())
        throw Error("", "the two-way study refines the adapted formulation, which --formulation leaves out",
                    "add adapted to --formulation, or give --no-two-way for curves only");
    if (o.sdps.empty()) throw Error("", "--sdp needs at least one node spacing");
    const double thinnest = o.panel.thickness;
    for (double s : o.sdps) {
        positive(s, "--sdp", "0.5");
        if (s > 0.5 * thinnest)
            throw Error("", "--sdp " + show(s) + " mm leaves fewer than two node spacings across the " +
                                show(thinnest) + " mm thickness",
                        "use node spacings below " + show(0.5 * thinnest) + " mm");
    }
    for (double s : o.originalSdps) {
        positive(s, "--sdp-original", "0.5");
        if (std::none_of(o.sdps.begin(), o.sdps.end(),
                         [&](double t) { return std::abs(t - s) <= 1e-12 * s; }))
            throw Error("", "--sdp-original " + show(s) + " is not one of the --sdp values",
                        "the original formulation runs at a subset of --sdp; list it there too");
    }
    auto checkVoxel = [&](double v, const std::string& option) {
        positive(v, option, "0.15");
        if (v * 4.0 > thinnest)
            throw Error("", option + " " + show(v) + " mm leaves fewer than 4 voxels across the " +
                                show(thinnest) + " mm thickness",
                        "use voxels of at most " + show(thinnest / 4.0) + " mm");
    };
    checkVoxel(o.fixedVdp, "--vdp-fixed");
    if (o.twoWay) {
        if (o.vdps.empty()) throw Error("", "--vdp needs at least one voxel size");
        for (double v : o.vdps) checkVoxel(v, "--vdp");
    }
    positive(o.tolerance, "--tolerance", "0.05");
    for (double d : o.snapshotDeltas)
        if (!(d >= 0.0 && d <= slabDeltaMax(o)))
            throw Error("", "--snapshots " + show(d) + " is outside [0, δ_max = " + show(slabDeltaMax(o)) + "]",
                        "give snapshot displacements between 0 and --delta-max");
    if (o.samples < 10 || o.samples > 100000) throw Error("", "--samples must be 10 to 100000");

    // Finite but absurd values (a crawling indenter, a feather-light block, microscopic voxels)
    // would run for years or exhaust memory: refuse them with the estimate.
    const SlabCostEstimate cost = estimateSlabCost(o);
    if (cost.steps > kMaxSlabSteps)
        throw Error("", "the study would take " + show(double(cost.steps)) + " time steps",
                    "check --speed, --density, --safety and the stiffnesses (the default is 1.6e5 steps)");
    if (cost.memoryBytes > kMaxSlabMemoryBytes)
        throw Error("", "the study would need about " + show(cost.memoryBytes / 1073741824.0) +
                            " GiB of memory (the budget is " + show(kMaxSlabMemoryBytes / 1073741824.0) +
                            " GiB)",
                    "use coarser --vdp / --vdp-fixed or --sdp");
}

SlabStiffness slabStiffness(const SlabStudyOptions& o)
{
    SlabStiffness k;
    // A traction p on a face shortens a block of length L by p·L/E: kn* = E/L.
    k.knStar = o.knStar > 0.0 ? o.knStar : o.material.youngModulus / o.panel.blockSize;
    k.ksStar = o.ksStar > 0.0 ? o.ksStar : k.knStar / (2.0 * (1.0 + o.material.poisson));
    const double sRef = o.referenceSdp > 0.0
                            ? o.referenceSdp
                            : *std::max_element(o.sdps.begin(), o.sdps.end());
    // A node's area on an equilateral mesh of edge s is (√3/2)·s².
    k.kn = o.knOriginal > 0.0 ? o.knOriginal : k.knStar * 0.5 * std::sqrt(3.0) * sRef * sRef;
    k.ks = k.kn * (k.ksStar / k.knStar);
    return k;
}

ContactModel slabContactModel(const SlabStudyOptions& o, Formulation formulation)
{
    const SlabStiffness k = slabStiffness(o);
    ContactModel m;
    m.formulation = formulation;
    m.testing = o.testing;
    m.normalStiffness = perArea(formulation) ? k.knStar : k.kn;
    // single-node and volume carry no shear springs (contact.md).
    const bool shear = normalModel(formulation).perNodeForces();
    m.shearStiffness = shear ? (perArea(formulation) ? k.ksStar : k.ks) : 0.0;
    m.friction = shear ? o.material.friction : 0.0;
    return m;
}

std::shared_ptr<const GrainAsset> bakeSlabBlock(const SlabPanel& panel, double vdp, double sdp)
{
    BakeOptions bake;
    bake.voxelSize = vdp;
    bake.nodePlacement = NodePlacement::Spacing;
    bake.nodeSpacing = sdp;
    bake.areaRule = AreaRule::Mesh;
    std::ostringstream text;
    const SlabPanelOptions& p = panel.options();
    text << "slab block L=" << p.blockSize << " t=" << p.thickness << " angle=" << p.angleDeg
         << " voxel " << vdp << " node_spacing " << sdp;
    bake.optionsText = text.str();
    std::vector<std::string> warnings;  // only "spacing finer than voxels", expected in a study
    return std::make_shared<const GrainAsset>(
        bakeMesh(panel.referenceMesh(), "slab block", bake, warnings));
}

double slabTimeStep(const SlabStudyOptions& o, const SlabPanel& panel, const GrainAsset& block,
                    Formulation formulation)
{
    const SlabStiffness k = slabStiffness(o);
    const double mass = o.material.density * block.mass.volume;
    // One shared face in full contact: kn*·A (adapted: the nodes' areas add up to A; symmetric
    // testing adds both sides at half weight), or kn per node on it (original).
    const double meanNodeArea = block.nodes.totalArea() / double(std::max<size_t>(1, block.nodes.size()));
    const ContactModel model = slabContactModel(o, formulation);
    const double face =
        model.normal().patchStiffness(model.normalStiffness, panel.sharedFaceArea(), meanNodeArea);
    // A block squeezed between its two x neighbours (the stiffest direction), with its shear
    // springs as stiff again along the faces.
    const double stiffest = 2.0 * face * std::max(1.0, k.ksStar / k.knStar);
    return o.timeStepSafety * 2.0 * std::sqrt(mass / stiffest);
}

Scene makeSlabScene(const SlabStudyOptions& o, Formulation formulation, const GrainAsset& block,
                    const std::string& assetPath, double dt)
{
    const SlabPanel panel(o.panel);
    Scene scene;
    scene.path = "slab_scene.toml";
    AssetSpec asset;
    asset.name = "block";
    asset.file = assetPath;
    asset.where = "slab block";
    scene.assets.push_back(asset);
    scene.materials.push_back({"glass", o.material.density});
    scene.materials.push_back({"rigid", 0.0});
    ContactSpec contact;
    contact.model = slabContactModel(o, formulation);
    contact.restitution = o.material.restitution;
    contact.materialA = contact.materialB = 0;
    contact.where = "blocks";
    scene.contacts.push_back(contact);
    contact.materialB = 1;
    contact.where = "blocks against the frame and the indenter";
    scene.contacts.push_back(contact);
    for (const SlabBlock& b : panel.blocks()) {
        GrainSpec g;
        g.name = b.name;
        g.asset = 0;
        g.material = 0;
        g.pose = slabBlockPose(b, block.inputFrame);
        g.where = b.name;
        scene.grains.push_back(g);
    }
    for (const SlabBlock& b : panel.frame()) {
        BoundarySpec f;
        f.name = b.name;
        f.shape = BoundaryShape::LevelSet;
        f.material = 1;
        f.asset = 0;
        f.pose = slabBlockPose(b, block.inputFrame);
        f.where = b.name;
        scene.boundaries.push_back(f);
    }
    BoundarySpec indenter;
    indenter.name = "indenter";
    indenter.shape = BoundaryShape::Sphere;
    indenter.material = 1;
    const Vec3 top = panel.blocks()[panel.centralBlock()].center +
                     Vec3(0, 0, 0.5 * o.panel.thickness);
    indenter.center = top + Vec3(0, 0, o.indenterRadius);  // touching the central block's top
    indenter.radius = o.indenterRadius;
    indenter.velocity = Vec3(0, 0, -o.speed);
    indenter.where = "indenter";
    scene.boundaries.push_back(indenter);
    scene.gravity = Vec3(0, 0, -o.material.gravity);
    scene.globalDamping = o.material.globalDamping;
    scene.timeStep.fixed = dt;
    scene.end.boundary = static_cast<int>(scene.boundaries.size()) - 1;
    scene.end.displacement = slabDeltaMax(o);
    const double duration = slabDeltaMax(o) / o.speed;
    scene.output.historyPeriod = duration / o.samples;
    scene.output.vtkPeriod = duration / 20.0;
    return scene;
}

std::string slabSceneToml(const Scene& scene, const SlabStudyOptions& o, const std::string& sceneDir)
{
    namespace fs = std::filesystem;
    std::ostringstream t;
    t << std::setprecision(17);
    auto vec = [&](const Vec3& v) {
        std::ostringstream s;
        s << std::setprecision(17) << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
        return s.str();
    };
    auto quat = [&](const Quat& q) {
        std::ostringstream s;
        s << std::setprecision(17) << "[" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]";
        return s.str();
    };
    const SlabStiffness k = slabStiffness(o);
    const ContactModel& m = scene.contacts.front().model;
    t << "# The interlocked slab of Feldfogel et al. (2024), Fig. 5 and 6, written by\n"
      << "# `lsdem-study slab`: " << o.panel.blocksPerSide << "x" << o.panel.blocksPerSide
      << " blocks, L = " << o.panel.blockSize << " mm, t = " << o.panel.thickness
      << " mm, interlocking angle " << o.panel.angleDeg << " deg (docs/slab.md).\n"
      << "# The frame is a ring of fixed level-set blocks of the same shape; a sphere pushes the\n"
      << "# central block down. Run with\n#   build/tools/lsdem-run slab_scene.toml --out slab-run\n"
      << "# slab-run/boundary_indenter.csv then holds P (fz) against the indenter's displacement.\n"
      << "# Units: mm, tonne, s, N. kn* = E/L = " << k.knStar << " N/mm^3 (E = "
      << o.material.youngModulus << " MPa).\n\n";
    t << "[units]\nlength = \"mm\"\nmass = \"tonne\"\ntime = \"s\"\nforce = \"N\"\n\n";
    for (const AssetSpec& a : scene.assets) {
        std::string path = a.file;
        std::error_code ec;
        const fs::path rel = fs::relative(fs::absolute(a.file), fs::absolute(sceneDir), ec);
        if (!ec && !rel.empty() && rel.string().rfind("..", 0) != 0) path = rel.string();
        t << "[assets." << a.name << "]\nfile = \"" << path << "\"   # baked by lsdem-study slab\n\n";
    }
    for (const MaterialSpec& mat : scene.materials)
        t << "[materials." << mat.name << "]\ndensity = " << mat.density
          << (mat.density > 0 ? "   # t/mm^3" : "   # rigid frame and indenter") << "\n\n";
    for (const ContactSpec& c : scene.contacts) {
        t << "[[contacts]]\nmaterials = [\"" << scene.materials[c.materialA].name << "\", \""
          << scene.materials[c.materialB].name << "\"]\n"
          << "formulation = \"" << formulationName(m.formulation) << "\"\n"
          << "testing = \"" << nodeTestingName(m.testing) << "\"\n"
          << "normal_stiffness = " << c.model.normalStiffness << "   # "
          << stiffnessUnit(c.model.formulation) << "\n";
        if (c.model.shearStiffness > 0) t << "shear_stiffness = " << c.model.shearStiffness << "\n";
        if (c.model.friction > 0) t << "friction = " << c.model.friction << "\n";
        t << "restitution = " << c.restitution << "\n\n";
    }
    for (const GrainSpec& g : scene.grains)
        t << "[[grains]]\nname = \"" << g.name << "\"\nasset = \"" << scene.assets[g.asset].name
          << "\"\nmaterial = \"" << scene.materials[g.material].name << "\"\nposition = "
          << vec(g.pose.position) << "\norientation = " << quat(g.pose.orientation) << "\n\n";
    for (const BoundarySpec& b : scene.boundaries) {
        t << "[[boundaries]]\nname = \"" << b.name << "\"\n";
        if (b.shape == BoundaryShape::LevelSet) {
            t << "type = \"level-set\"\nasset = \"" << scene.assets[b.asset].name
              << "\"\nmaterial = \"" << scene.materials[b.material].name << "\"\nposition = "
              << vec(b.pose.position) << "\norientation = " << quat(b.pose.orientation) << "\n\n";
        } else {
            t << "type = \"sphere\"\nmaterial = \"" << scene.materials[b.material].name
              << "\"\ncenter = " << vec(b.center) << "\nradius = " << b.radius
              << "\nvelocity = " << vec(b.velocity) << "   # mm/s\n\n";
        }
    }
    t << "[simulation]\ngravity = " << vec(scene.gravity) << "\nglobal_damping = "
      << scene.globalDamping << "\ntime_step = " << scene.timeStep.fixed
      << "   # safety x the stability limit of a block between two neighbours\n"
      << "end_displacement = { boundary = \"" << scene.boundaries[scene.end.boundary].name
      << "\", value = " << scene.end.displacement << " }\n\n";
    t << "[output]\nhistory_period = " << scene.output.historyPeriod
      << "\nvtk_period = " << scene.output.vtkPeriod << "\n";
    return t.str();
}

SlabRunResult runSlabCase(const SlabStudyOptions& o, const SlabPanel& panel,
                          std::shared_ptr<const GrainAsset> block, const std::string& assetPath,
                          Formulation f, double sdp, double vdp,
                          const std::function<void(double)>& progress)
{
    const auto start = SteadyClock::now();
    SlabRunResult r;
    r.formulation = f;
    r.sdp = sdp;
    r.vdp = vdp;
    r.nodes = static_cast<int>(block->nodes.size());
    r.meanSpacing = block->spacing.mean;
    r.stiffness = slabContactModel(o, f).normalStiffness;
    r.dt = slabTimeStep(o, panel, *block, f);

    const Scene scene = makeSlabScene(o, f, *block, assetPath, r.dt);
    std::vector<std::string> warnings;
    World world = buildWorld(scene, warnings);
    Simulation sim(std::move(world), r.dt);
    const World& w = sim.world();
    const int indenter = static_cast<int>(w.boundaries.size()) - 1;
    const int centre = panel.centralBlock();
    const int count = static_cast<int>(w.grains.size());
    std::vector<Vec3> p0(count);
    std::vector<Quat> q0(count);
    for (int k = 0; k < count; ++k) {
        p0[k] = w.grains[k].body.pose.position;
        q0[k] = w.grains[k].body.pose.orientation;
    }
    // The reference block's origin in the asset frame: where a block's rest centre goes.
    const Vec3 origin = -(block->inputFrame.rotation * block->inputFrame.centroid);

    const double deltaMax = slabDeltaMax(o);
    const long long totalSteps = static_cast<long long>(std::ceil(deltaMax / (o.speed * r.dt)));
    const long long recordEvery = std::max<long long>(1, totalSteps / o.samples);
    const std::vector<double> targets = snapshotDeltasOf(o);
    size_t nextSnapshot = 0;

    auto sample = [&](double delta) {
        SlabSample s;
        s.delta = delta;
        s.force = w.boundaries[indenter].force.z();
        s.centralDrop = -(w.grains[centre].body.pose.position - p0[centre]).z();
        for (int k = 0; k < count; ++k)
            if (k != centre)
                s.othersMax = std::max(s.othersMax, (w.grains[k].body.pose.position - p0[k]).norm());
        for (int b = 0; b < indenter; ++b) s.frameForce -= w.boundaries[b].force.z();
        s.kinetic = sim.energies().kinetic;
        r.curve.push_back(s);
    };
    auto snapshot = [&](double delta) {
        SlabSnapshot s;
        s.delta = delta;
        for (int k = 0; k < count; ++k) {
            const RigidPose& pose = w.grains[k].body.pose;
            s.displacement.push_back(pose.position - p0[k]);
            const Mat3 turn = (pose.orientation * q0[k].conjugate()).toRotationMatrix();
            s.faces.push_back(panel.faces(panel.blocks()[k], turn, pose.toWorld(origin)));
        }
        r.snapshots.push_back(std::move(s));
    };
    auto delta = [&] { return -w.boundaries[indenter].displacement.z(); };
    auto takeSnapshots = [&](double d) {
        while (nextSnapshot < targets.size() && d >= targets[nextSnapshot] - 1e-9 * deltaMax) {
            snapshot(d);
            ++nextSnapshot;
        }
    };

    sample(0.0);
    takeSnapshots(0.0);
    SteadyClock::time_point lastReport = SteadyClock::now();
    try {
        while (delta() < deltaMax * (1.0 - 1e-12)) {
            sim.step();
            ++r.steps;
            const double d = delta();
            if (r.steps % recordEvery == 0 || d >= deltaMax * (1.0 - 1e-12)) sample(d);
            takeSnapshots(d);
            if (progress && secondsSince(lastReport) > 10.0) {
                progress(d);
                lastReport = SteadyClock::now();
            }
        }
    } catch (const Error& e) {
        // Keep what was recorded; the caller reports the failure.
        r.stopped = true;
        r.error = e.what();
        if (r.curve.empty() || r.curve.back().delta != delta()) sample(delta());
    }
    for (int k = 0; k < count; ++k) r.finalDisplacement.push_back(w.grains[k].body.pose.position - p0[k]);
    r.nodeChecks = sim.counters().nodes.nodesConsidered;
    r.stabilityLimit = sim.stabilityLimitSeen();
    r.runSeconds = secondsSince(start);
    return r;
}

double slabCurveDifference(const std::vector<SlabSample>& a, const std::vector<SlabSample>& b,
                           bool wholeCurve)
{
    if (a.size() < 2 || b.empty()) return std::numeric_limits<double>::infinity();
    double peakA = 0.0, peakB = 0.0, peakDelta = 0.0;
    for (const SlabSample& s : a) peakA = std::max(peakA, s.force);
    for (const SlabSample& s : b)
        if (s.force > peakB) {
            peakB = s.force;
            peakDelta = s.delta;
        }
    if (!(peakB > 0.0)) return std::numeric_limits<double>::infinity();
    const double end = wholeCurve ? b.back().delta : peakDelta;
    double sum = 0.0;
    int count = 0;
    size_t k = 0;
    for (const SlabSample& s : b) {
        if (s.delta > end || s.delta > a.back().delta) break;
        while (k + 2 < a.size() && a[k + 1].delta < s.delta) ++k;
        const SlabSample &u = a[k], &v = a[k + 1];
        const double span = v.delta - u.delta;
        const double w = span > 0 ? std::clamp((s.delta - u.delta) / span, 0.0, 1.0) : 0.0;
        const double pa = u.force + w * (v.force - u.force);
        sum += (pa - s.force) * (pa - s.force);
        ++count;
    }
    if (count == 0) return std::numeric_limits<double>::infinity();
    const double rms = std::sqrt(sum / count) / peakB;
    return wholeCurve ? rms : std::max(rms, std::abs(peakA - peakB) / peakB);
}

namespace {

/// How far the blocks around the centre moved at the end of a run.
struct BlockMotion
{
    double neighbours = 0, diagonal = 0, rest = 0;  ///< largest displacement per ring, mm
    int farMoved = 0;                               ///< other blocks moved more than t/3
    std::string farNames;
};

BlockMotion blockMotion(const SlabPanel& panel, const SlabRunResult& run)
{
    BlockMotion m;
    const int centre = panel.centralBlock();
    const std::vector<SlabBlock>& blocks = panel.blocks();
    for (int k = 0; k < static_cast<int>(blocks.size()); ++k) {
        if (k == centre) continue;
        const double d = run.finalDisplacement[k].norm();
        const int di = std::abs(blocks[k].i - blocks[centre].i), dj = std::abs(blocks[k].j - blocks[centre].j);
        double& ring = di + dj == 1 ? m.neighbours : std::max(di, dj) == 1 ? m.diagonal : m.rest;
        ring = std::max(ring, d);
        if (d > panel.options().thickness / 3) {
            ++m.farMoved;
            m.farNames += " " + blocks[k].name + " (" + show(std::round(d * 100) / 100) + " mm)";
        }
    }
    return m;
}

} // namespace

SlabFailureMode slabFailureMode(const SlabPanel& panel, const SlabRunResult& run)
{
    if (run.finalDisplacement.size() != panel.blocks().size() || run.curve.empty())
        return SlabFailureMode::None;
    const BlockMotion m = blockMotion(panel, run);
    const double drop = -run.finalDisplacement[panel.centralBlock()].z();
    const double delta = run.curve.back().delta;
    const double others = std::max({m.neighbours, m.diagonal, m.rest});
    if (drop > 0.5 * delta && others < 0.25 * drop && m.farMoved == 0) return SlabFailureMode::PushOut;
    if (m.farMoved > 0) return SlabFailureMode::BlocksDisplaced;
    return SlabFailureMode::Deflection;
}

std::string slabFailureModeName(SlabFailureMode mode)
{
    switch (mode) {
    case SlabFailureMode::PushOut: return "push-out";
    case SlabFailureMode::BlocksDisplaced: return "blocks-displaced";
    case SlabFailureMode::Deflection: return "deflection";
    case SlabFailureMode::None: break;
    }
    return "none";
}

std::string slabFailureSummary(const SlabPanel& panel, const SlabRunResult& run)
{
    std::ostringstream s;
    s << std::fixed << std::setprecision(3);
    const int n = panel.n(), centre = panel.centralBlock();
    if (run.finalDisplacement.size() != panel.blocks().size()) return "no result\n";
    const double delta = run.curve.empty() ? 0.0 : run.curve.back().delta;
    const BlockMotion m = blockMotion(panel, run);
    const Vec3 c = run.finalDisplacement[centre];
    s << formulationName(run.formulation) << ", SDP " << run.sdp << " mm, VDP " << run.vdp
      << " mm (" << run.nodes << " nodes per block), at delta = " << delta << " mm:\n";
    if (run.stopped) s << "  the run stopped early: " << run.error << "\n";
    s << "  central block " << panel.blocks()[centre].name << " moved down by " << -c.z()
      << " mm (sideways " << c.head<2>().norm() << " mm)\n"
      << "  its 4 face neighbours moved at most " << m.neighbours << " mm, the 4 diagonal ones "
      << m.diagonal << " mm";
    if (n > 3) s << ", the other " << n * n - 9 << " blocks " << m.rest << " mm";
    s << "\n";
    switch (slabFailureMode(panel, run)) {
    case SlabFailureMode::PushOut:
        s << "  => push-out of the central block; the rest of the panel stays largely intact\n";
        break;
    case SlabFailureMode::BlocksDisplaced:
        s << "  => " << m.farMoved << " other block(s) moved more than t/3 and stayed:"
          << m.farNames << "\n";
        break;
    default: s << "  => the panel deflects as a whole (no block pushed out)\n";
    }
    return s.str();
}

int slabConvergedRun(const SlabPanel& panel, const std::vector<SlabRunResult>& runs,
                     const std::vector<int>& series, double tolerance, bool& converged)
{
    converged = false;
    if (series.empty()) return -1;
    const int finest = series.back();
    if (runs[finest].stopped) return finest;  // no reference to converge to
    const SlabFailureMode mode = slabFailureMode(panel, runs[finest]);
    int chosen = finest;
    for (int k = int(series.size()) - 2; k >= 0; --k) {
        const SlabRunResult& r = runs[series[k]];
        if (r.stopped || slabFailureMode(panel, r) != mode ||
            slabCurveDifference(r.curve, runs[finest].curve) > tolerance)
            break;
        chosen = series[k];
        converged = true;
    }
    return chosen;
}

SlabCostEstimate estimateSlabCost(const SlabStudyOptions& o)
{
    SlabCostEstimate e;
    const SlabPanel panel(o.panel);
    const double area = blockSurfaceArea(panel);
    const double blocks = double(panel.n()) * panel.n();
    const SlabStiffness k = slabStiffness(o);
    const double mass = o.material.density * panel.blockVolume();
    // Measured on this machine (2 shared cores, see docs/slab.md): about 75 ns of wall time
    // per block node and step, both directions of symmetric testing and the shear history
    // included.
    const double secondsPerNodeStep = 75e-9;
    struct RunCost
    {
        double seconds = 0.0, nodes = 0.0, bytes = 0.0;
        long long steps = 0;
    };
    auto runCost = [&](Formulation f, double sdp, double vdp) {
        RunCost c;
        c.nodes = nodesForSpacing(area, sdp);
        const ContactModel model = slabContactModel(o, f);
        const double face = model.normal().patchStiffness(
            model.normalStiffness, panel.sharedFaceArea(), area / c.nodes);
        const double dt =
            o.timeStepSafety * 2.0 * std::sqrt(mass / (2.0 * face * std::max(1.0, k.ksStar / k.knStar)));
        // Clamped before the cast: absurd inputs are refused by the caller, not undefined here.
        c.steps = static_cast<long long>(std::min(std::ceil(slabDeltaMax(o) / (o.speed * dt)), 1e15));
        c.seconds = c.steps * blocks * c.nodes * secondsPerNodeStep;
        // The peak is the bake: measured 816 MB resident for the block at VDP 0.025 mm (a
        // 58 MiB asset), about 48 bytes per voxel of the block's padded bounding box. Then
        // the run: nodes (position, normal, area) and the shear history per node in contact
        // (a std::map entry, ~80 bytes) for about half the nodes of every block.
        const double box = (o.panel.blockSize + 2 * panel.overhang() + 10 * vdp) *
                           (o.panel.blockSize + 2 * panel.overhang() + 10 * vdp) *
                           (o.panel.thickness + 10 * vdp);
        c.bytes = 48.0 * box / (vdp * vdp * vdp) + c.nodes * 56.0 + blocks * c.nodes * 0.5 * 80.0;
        return c;
    };
    // Counted runs: the upper bound's (stage 2 at the finest SDP).
    auto count = [&](const RunCost& c) {
        ++e.runs;
        e.steps += c.steps;
        e.seconds += c.seconds;
        e.nodesPerBlockFinest = std::max(e.nodesPerBlockFinest, c.nodes);
        e.memoryBytes = std::max(e.memoryBytes, c.bytes);
    };
    const std::vector<double> sdps = coarseToFine(o.sdps);
    for (double s : sdps)
        for (Formulation f : o.formulations)
            if (runsAt(o, f, s)) count(runCost(f, s, o.fixedVdp));
    e.secondsAtLeast = e.seconds;
    if (o.twoWay) {
        // Stage 2 runs at the converged SDP, not known yet: it costs least at the coarsest SDP
        // and most at the finest.
        const std::vector<double> vdps = coarseToFine(o.vdps);
        for (double v : vdps) {
            if (std::abs(v - o.fixedVdp) <= 1e-12) continue;  // shared with stage 1
            e.secondsAtLeast += runCost(Formulation::Adapted, sdps.front(), v).seconds;
            count(runCost(Formulation::Adapted, sdps.back(), v));
        }
        const RunCost coarse = runCost(Formulation::Adapted, sdps.front(), vdps.front());  // snapshots
        e.secondsAtLeast += coarse.seconds;
        count(coarse);
    }
    std::ostringstream t;
    t << std::setprecision(3) << e.runs << " runs, " << e.steps << " steps in all, up to "
      << e.nodesPerBlockFinest << " nodes per block x " << blocks << " blocks; about ";
    if (e.secondsAtLeast < 0.99 * e.seconds)
        t << e.secondsAtLeast / 60.0 << " to " << e.seconds / 60.0
          << " min on 2 cores (stage 2 runs at the converged SDP: from the coarsest to the finest), ";
    else
        t << e.seconds / 60.0 << " min on 2 cores, ";
    t << "peak memory about " << e.memoryBytes / 1048576.0 << " MiB";
    e.text = t.str();
    return e;
}

SlabStudyResult runSlabStudy(const SlabStudyOptions& o, std::ostream* log,
                             const std::function<void(const SlabStudyResult&)>& afterEachRun)
{
    namespace fs = std::filesystem;
    checkSlabStudyOptions(o);
    const auto start = SteadyClock::now();
    const SlabPanel panel(o.panel);
    SlabStudyResult result;
    const std::string assetDir = o.outDir + "/assets";
    fs::create_directories(assetDir);

    // Baked blocks by (SDP, VDP), each saved so that the scenes (and lsdem-run) can read it.
    std::map<std::pair<double, double>, std::pair<std::shared_ptr<const GrainAsset>, std::string>> baked;
    auto blockFor = [&](double sdp, double vdp) {
        const auto key = std::make_pair(sdp, vdp);
        auto it = baked.find(key);
        if (it != baked.end()) return it->second;
        const auto t0 = SteadyClock::now();
        auto asset = bakeSlabBlock(panel, vdp, sdp);
        std::ostringstream name;
        name << assetDir << "/block_sdp" << sdp << "_vdp" << vdp << ".vdb";
        saveAsset(*asset, name.str());
        if (log)
            *log << "  baked SDP " << sdp << " mm, VDP " << vdp << " mm: " << asset->nodes.size()
                 << " nodes per block (mean spacing " << std::setprecision(3)
                 << asset->spacing.mean << " mm) in " << secondsSince(t0) << " s\n"
                 << std::flush;
        baked.clear();  // one block in memory at a time
        return baked[key] = {asset, name.str()};
    };
    auto run = [&](Formulation f, double sdp, double vdp, const std::string& stage) {
        for (size_t k = 0; k < result.runs.size(); ++k) {
            const SlabRunResult& r = result.runs[k];
            if (r.formulation == f && r.sdp == sdp && r.vdp == vdp) return int(k);
        }
        const auto bakeStart = SteadyClock::now();
        const auto [asset, path] = blockFor(sdp, vdp);
        const double bakeSeconds = secondsSince(bakeStart);
        if (log)
            *log << "  " << formulationName(f) << ", SDP " << sdp << ", VDP " << vdp << ": "
                 << std::flush;
        SlabRunResult r = runSlabCase(o, panel, asset, path, f, sdp, vdp, [&](double d) {
            if (log) *log << "δ = " << std::setprecision(3) << d << " mm ... " << std::flush;
        });
        r.bakeSeconds = bakeSeconds;
        if (log) {
            double peak = 0;
            for (const SlabSample& s : r.curve) peak = std::max(peak, s.force);
            *log << r.steps << " steps of " << std::setprecision(3) << r.dt << " s in "
                 << r.runSeconds << " s, peak P = " << peak << " N"
                 << (r.stopped ? " (STOPPED: " + r.error + ")" : "") << "\n"
                 << std::flush;
        }
        result.runs.push_back(std::move(r));
        result.stage.push_back(stage);
        result.wallSeconds = secondsSince(start);
        if (afterEachRun) afterEachRun(result);
        return int(result.runs.size()) - 1;
    };

    // Stage 1: SDP refined at fixed VDP, every formulation.
    const std::vector<double> sdps = coarseToFine(o.sdps);
    if (log) *log << "stage 1: SDP refined at VDP = " << o.fixedVdp << " mm\n";
    std::vector<int> adaptedBySdp;
    for (double s : sdps)
        for (Formulation f : o.formulations) {
            if (!runsAt(o, f, s)) continue;
            const int k = run(f, s, o.fixedVdp, "sdp");
            result.sdpSeries[f].push_back(k);
            if (f == Formulation::Adapted) adaptedBySdp.push_back(k);
        }

    const int sdpRun = slabConvergedRun(panel, result.runs, adaptedBySdp, o.tolerance, result.sdpConverged);
    result.convergedSdp = sdpRun >= 0 ? result.runs[sdpRun].sdp : sdps.back();
    result.convergedVdp = o.fixedVdp;
    result.convergedRun = sdpRun;

    if (o.twoWay && sdpRun >= 0) {
        const std::vector<double> vdps = coarseToFine(o.vdps);
        if (log)
            *log << "stage 2: VDP refined at SDP = " << result.convergedSdp << " mm (adapted)\n";
        std::vector<int> byVdp;
        for (double v : vdps) byVdp.push_back(run(Formulation::Adapted, result.convergedSdp, v, "vdp"));
        result.vdpSeries = byVdp;
        const int vdpRun = slabConvergedRun(panel, result.runs, byVdp, o.tolerance, result.vdpConverged);
        result.convergedVdp = result.runs[vdpRun].vdp;
        result.convergedRun = vdpRun;
        // The coarse case of the snapshots: coarsest SDP and coarsest VDP.
        result.coarseRun = run(Formulation::Adapted, sdps.front(), vdps.front(), "coarse");
    } else if (!adaptedBySdp.empty()) {
        result.coarseRun = adaptedBySdp.front();
    }
    result.wallSeconds = secondsSince(start);
    return result;
}

void writeSlabOutputs(const SlabStudyResult& result, const SlabStudyOptions& o,
                      const SlabPanel& panel)
{
    const SlabStiffness k = slabStiffness(o);
    std::ostringstream head;
    head << "# lsdem slab study: " << o.panel.blocksPerSide << "x" << o.panel.blocksPerSide
         << " blocks, L=" << o.panel.blockSize << " mm, t=" << o.panel.thickness
         << " mm, angle=" << o.panel.angleDeg << " deg, indenter R=" << o.indenterRadius
         << " mm at " << o.speed << " mm/s; kn*=" << k.knStar << " N/mm^3, ks*=" << k.ksStar
         << " N/mm^3, kn=" << k.kn << " N/mm, ks=" << k.ks << " N/mm, mu=" << o.material.friction
         << ", testing=" << nodeTestingName(o.testing) << "; force in N, lengths in mm\n";
    auto label = [](const SlabRunResult& r) {
        std::ostringstream s;
        s << formulationName(r.formulation) << " SDP " << r.sdp << " VDP " << r.vdp;
        return s.str();
    };

    std::ostringstream curves;
    curves << std::setprecision(10) << head.str()
           << "run,formulation,sdp,vdp,nodes,delta,P,central_drop,others_max,frame_force,kinetic\n";
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const SlabRunResult& r = result.runs[i];
        for (const SlabSample& s : r.curve)
            curves << i << ',' << formulationName(r.formulation) << ',' << r.sdp << ',' << r.vdp
                   << ',' << r.nodes << ',' << s.delta << ',' << s.force << ',' << s.centralDrop
                   << ',' << s.othersMax << ',' << s.frameForce << ',' << s.kinetic << '\n';
    }
    writeTextFileAtomically(o.outDir + "/slab.csv", curves.str());

    // Each run against the finest of its refinement series (stage 1 of its formulation, and
    // stage 2); empty where it is not a member.
    std::ostringstream runs;
    runs << std::setprecision(10) << head.str()
         << "run,stage,role,formulation,sdp,vdp,vdp_over_sdp,nodes,spacing_measured,stiffness,dt,"
            "stability_limit,steps,bake_s,run_s,node_checks,P_max,delta_at_P_max,central_drop,"
            "others_max,diff_sdp_series,diff_vdp_series,diff_whole_curve,failure_mode,stopped\n";
    auto seriesDifference = [&](const std::vector<int>& series, int i, bool whole) {
        if (std::find(series.begin(), series.end(), i) == series.end()) return std::string();
        return show(slabCurveDifference(result.runs[i].curve, result.runs[series.back()].curve, whole));
    };
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const SlabRunResult& r = result.runs[i];
        const auto own = result.sdpSeries.find(r.formulation);
        const std::vector<int> none;
        const std::vector<int>& sdpSeries = own != result.sdpSeries.end() ? own->second : none;
        const std::string diffSdp = seriesDifference(sdpSeries, int(i), false);
        const std::string diffVdp = seriesDifference(result.vdpSeries, int(i), false);
        std::string whole = seriesDifference(sdpSeries, int(i), true);
        if (whole.empty()) whole = seriesDifference(result.vdpSeries, int(i), true);
        double peak = 0, at = 0;
        for (const SlabSample& s : r.curve)
            if (s.force > peak) {
                peak = s.force;
                at = s.delta;
            }
        const std::string role = int(i) == result.convergedRun ? "converged"
                                 : int(i) == result.coarseRun  ? "coarse"
                                                               : "";
        runs << i << ',' << result.stage[i] << ',' << role << ',' << formulationName(r.formulation)
             << ',' << r.sdp << ',' << r.vdp << ',' << r.vdp / r.sdp << ',' << r.nodes << ','
             << r.meanSpacing << ',' << r.stiffness << ',' << r.dt << ',' << r.stabilityLimit << ','
             << r.steps << ','
             << r.bakeSeconds << ',' << r.runSeconds << ',' << r.nodeChecks << ',' << peak << ','
             << at << ',' << (r.curve.empty() ? 0.0 : r.curve.back().centralDrop) << ','
             << (r.curve.empty() ? 0.0 : r.curve.back().othersMax) << ',' << diffSdp << ','
             << diffVdp << ',' << whole
             << ',' << slabFailureModeName(slabFailureMode(panel, r)) << ',' << (r.stopped ? 1 : 0)
             << '\n';
    }
    writeTextFileAtomically(o.outDir + "/slab_runs.csv", runs.str());

    // Snapshots of the coarse and the converged runs: every face of every block.
    std::ostringstream snaps;
    snaps << std::setprecision(8) << head.str()
          << "run,role,label,delta,block,i,j,displacement,face,x0,y0,z0,x1,y1,z1,x2,y2,z2,x3,y3,z3\n";
    for (int i : {result.coarseRun, result.convergedRun}) {
        if (i < 0) continue;
        const SlabRunResult& r = result.runs[i];
        const std::string role = i == result.convergedRun ? "converged" : "coarse";
        for (const SlabSnapshot& s : r.snapshots)
            for (size_t b = 0; b < s.faces.size(); ++b)
                for (int f = 0; f < 6; ++f) {
                    snaps << i << ',' << role << ',' << label(r) << ',' << s.delta << ','
                          << panel.blocks()[b].name << ',' << panel.blocks()[b].i << ','
                          << panel.blocks()[b].j << ',' << s.displacement[b].norm() << ',' << f;
                    for (const Vec3& c : s.faces[b][f].corners)
                        snaps << ',' << c.x() << ',' << c.y() << ',' << c.z();
                    snaps << '\n';
                }
        if (result.coarseRun == result.convergedRun) break;
    }
    writeTextFileAtomically(o.outDir + "/slab_snapshots.csv", snaps.str());

    std::ostringstream text;
    text << "Failure of the panel at delta_max = " << slabDeltaMax(o) << " mm, per run\n\n";
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const std::string role = int(i) == result.convergedRun ? " [converged]"
                                 : int(i) == result.coarseRun  ? " [coarse]"
                                                               : "";
        text << "run " << i << " (" << result.stage[i] << ")" << role << ": "
             << slabFailureSummary(panel, result.runs[i]) << "\n";
    }
    writeTextFileAtomically(o.outDir + "/slab_failure.txt", text.str());

    if (o.writeScene && result.convergedRun >= 0) {
        const SlabRunResult& r = result.runs[result.convergedRun];
        std::ostringstream name;
        name << o.outDir << "/assets/block_sdp" << r.sdp << "_vdp" << r.vdp << ".vdb";
        if (std::filesystem::exists(name.str())) {
            const auto asset = loadAsset(name.str());
            const Scene scene = makeSlabScene(o, r.formulation, *asset, name.str(), r.dt);
            writeTextFileAtomically(o.outDir + "/slab_scene.toml", slabSceneToml(scene, o, o.outDir));
        }
        writeMesh(panel.referenceMesh(), o.outDir + "/slab_block.obj");
    }
}

SlabStudyOptions slabFullOptions()
{
    SlabStudyOptions o;
    o.sdps = {1.0, 0.7, 0.5, 0.35, 0.25, 0.18, 0.125};
    o.originalSdps = {1.0, 0.7, 0.5, 0.35, 0.25};
    o.fixedVdp = 0.035;
    o.vdps = {0.4, 0.28, 0.2, 0.14, 0.1, 0.07, 0.05, 0.035};
    return o;
}

} // namespace lsdem

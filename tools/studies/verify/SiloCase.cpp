// The bulk case of the suite: a flat-bottomed cylindrical silo filled with grains and emptied
// through circular orifices of several sizes, the mass flow against Beverloo's law
// (BeverlooFit.h). Spheres and the bundled sand grains; the adapted law throughout (a bulk
// flow of thousands of grains: the single-contact cases above compare the laws).
#include "studies/verify/BeverlooChecks.h"
#include "studies/verify/BeverlooFit.h"
#include "studies/verify/SiloFill.h"
#include "studies/verify/SiloParking.h"
#include "studies/verify/SiloPlan.h"
#include "studies/verify/VerifyCases.h"

#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/scene/Packing.h"
#include "lsdem/simulation/Simulation.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <tuple>

namespace lsdem::verify {

namespace {

/// Grains of one kind: the packing's mixture and their size d for Beverloo's law.
struct GrainKind
{
    std::string name;
    std::vector<PackingComponent> mixture;
    double size = 0.0;  ///< d: the mean volume-equivalent diameter, mm
};

double equivalentDiameter(const GrainAsset& a)
{
    return std::cbrt(6.0 * a.mass.volume / kPi);
}

GrainKind spheres(Context& c, bool quick)
{
    GrainKind k;
    k.name = "spheres";
    k.mixture.push_back({"sphere", c.bodies.sphere(0.5, quick ? 100 : 200, 0.05), 1.0});
    k.size = equivalentDiameter(*k.mixture[0].asset);
    return k;
}

/// The bundled sand grains (assets/meshes/sand, equivalent diameter about 1 mm), in equal
/// shares, baked as sand.toml bakes them but with as many nodes as the spheres.
GrainKind sand(Context& c)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(c.sandMeshes, ec))
        if (e.is_regular_file() && e.path().extension() == ".obj") files.push_back(e.path().string());
    if (ec || files.empty())
        throw Error(c.sandMeshes, "no sand grain meshes (.obj) here",
                    "run from lsdem's folder (the default is assets/meshes/sand), give "
                    "--sand-meshes, or leave the silo out with --case");
    std::sort(files.begin(), files.end());
    GrainKind k;
    k.name = "sand";
    double sum = 0.0;
    for (const std::string& file : files) {
        BakeOptions o;
        o.voxelSize = 0.05;
        o.nodePlacement = NodePlacement::Count;
        o.nodeCount = 200;
        std::vector<std::string> warnings;
        auto asset = std::make_shared<const GrainAsset>(bakeMeshFile(file, o, warnings));
        sum += equivalentDiameter(*asset);
        k.mixture.push_back({fs::path(file).stem().string(), asset, 1.0});
    }
    k.size = sum / double(k.mixture.size());
    return k;
}

ContactModel siloLaw(const SiloPlan& p)
{
    ContactModel m;
    m.formulation = Formulation::Adapted;
    m.normalStiffness = p.knStar;
    m.shearStiffness = p.ksStar;
    m.friction = p.friction;
    m.damping = ViscousDamping(p.restitution);
    return m;
}

/// The filled silo closed by a flat floor at the plate's upper face: the packing generator's
/// grains (deposited in its own units), under the real law, gravity and materials.
Scene filledSilo(const SiloPlan& p, const GrainKind& kind, const PackingResult& packed)
{
    Setup material;
    material.density = p.density;
    Scene s = caseScene(material, siloLaw(p));
    for (const PackingComponent& component : kind.mixture) {
        AssetSpec a;
        a.name = component.name;
        a.loaded = component.asset;
        a.where = "silo case";
        s.assets.push_back(a);
    }
    for (GrainSpec g : packed.scene.grains) {
        g.material = 0;
        s.grains.push_back(g);
    }
    addWall(s, Vec3(0, 0, 0.5 * p.plateThickness), Vec3::UnitZ());
    BoundarySpec side;
    side.name = "silo";
    side.shape = BoundaryShape::Cylinder;
    side.material = 1;
    side.radius = p.siloRadius;
    s.boundaries.push_back(side);
    s.gravity = Vec3(0, 0, -p.gravity);
    return s;
}

/// One orifice's discharge: when each grain left (its whole bounding sphere below the plate)
/// and the mass out by then, in that order.
struct DischargeRun
{
    std::vector<double> times, masses;
    int outsideTheHole = 0;  ///< grains that came out anywhere but through the hole
    bool clogged = false;
    LineFit steady;          ///< M(t) over the measured window
    std::vector<VerifyFrame> frames;
};

DischargeRun discharge(const World& settled, const SiloPlan& p, double orifice, double dt,
                       double size, bool recordFrames)
{
    World w = settled;  // the fill as it settled, its shear histories included
    // The floor becomes the orifice plate: the same upper face, now with a hole.
    Boundary& floor = w.boundaries[0];
    floor.shape = BoundaryShape::Orifice;
    floor.center = Vec3::Zero();
    floor.axis = Vec3::UnitZ();
    floor.radius = 0.5 * orifice;
    floor.thickness = p.plateThickness;
    double largestRadius = 0.0;
    for (const Grain& g : w.grains) largestRadius = std::max(largestRadius, g.asset->boundingRadius);
    Simulation sim(std::move(w), dt);
    Parking parking(p.siloRadius, largestRadius);
    const double start = sim.world().time, lower = -0.5 * p.plateThickness;
    std::vector<char> out(sim.world().grains.size(), 0);
    DischargeRun run;
    double lastOut = start, mass = 0.0, nextFrame = start;
    while (int(run.times.size()) < p.countTo) {
        if (recordFrames && int(run.frames.size()) < p.frames && sim.world().time >= nextFrame) {
            VerifyFrame frame;
            frame.time = sim.world().time - start;
            for (const Grain& g : sim.world().grains)
                if (g.isFree()) frame.grains.push_back({g.asset, g.body.pose});
            run.frames.push_back(std::move(frame));
            nextFrame += p.framePeriod;
        }
        sim.step();
        World& now = sim.world();
        for (size_t i = 0; i < now.grains.size(); ++i) {
            Grain& g = now.grains[i];
            if (!g.isFree()) continue;
            const Vec3& x = g.body.pose.position;
            if (!out[i] && x.z() < lower - g.asset->boundingRadius) {
                out[i] = 1;
                mass += g.body.mass;
                run.times.push_back(now.time - start);
                run.masses.push_back(mass);
                if (std::hypot(x.x(), x.y()) > 0.5 * orifice) ++run.outsideTheHole;
                lastOut = now.time;
            }
            if (out[i] && x.z() < lower - 4.0 * size) parking.park(g);
        }
        if (now.time - lastOut > p.clogTime) {
            run.clogged = true;
            break;
        }
    }
    if (!run.clogged) {
        const auto from = run.times.begin() + p.countFrom;
        run.steady = fitLine(std::vector<double>(from, run.times.end()),
                             std::vector<double>(run.masses.begin() + p.countFrom, run.masses.end()));
    }
    return run;
}

/// The fill: the packing generator deposits the grains layer by layer in the closed silo.
PackingResult packedFill(const SiloPlan& p, const GrainKind& kind)
{
    PackingOptions fill;
    fill.mixture = kind.mixture;
    fill.cylinder = PackingCylinder{0.0, 0.0, p.siloRadius, 0.5 * p.plateThickness,
                                    0.5 * p.plateThickness + 2.0 * p.fillHeight};
    fill.count = p.grains;
    fill.friction = p.friction;
    fill.seed = 7;
    PackingResult packed = generatePacking(fill);
    if (!packed.complete)
        throw Error("", "silo: the packing generator fitted " +
                            std::to_string(packed.scene.grains.size()) + " of " +
                            std::to_string(p.grains) + " grains",
                    "a bug in the silo's plan: the silo is too small for its grains");
    return packed;
}

/// One orifice's checks: every grain out through the hole, no clog, a steady flow.
void addDischargeChecks(Context& c, const std::string& where, const SiloPlan& p,
                        const DischargeRun& run)
{
    c.report.add({where, "adapted", "grains out through the hole", "", 1.0,
                  run.times.empty() ? 0.0 : 1.0 - double(run.outsideTheHole) / double(run.times.size()),
                  1.0, 0.0, "every grain leaves through the orifice, none through the plate"});
    c.report.add({where, "adapted", "flow without clogging", "", 1.0, run.clogged ? 0.0 : 1.0,
                  1.0, 0.0,
                  "a grain out at least every " + numberText(p.clogTime) +
                      " s; D ≥ 5 d clogs rarely (Zuriguel et al. 2005)"});
    if (run.clogged) return;
    c.report.add({where, "adapted", "steady flow: R² of M(t)", "", 1.0, run.steady.rSquared, 1.0,
                  0.01,
                  "Beverloo's premise: a constant flow; M(t) a line over grains " +
                      std::to_string(p.countFrom) + "–" + std::to_string(p.countTo) +
                      " out (R² ≥ 0.99)"});
}

void runKind(Context& c, const SiloPlan& p, const GrainKind& kind)
{
    const PackingResult packed = packedFill(p, kind);
    // Settle under the real law and gravity, then open each orifice in turn on that fill.
    const Scene scene = filledSilo(p, kind, packed);
    const double dt = automaticTimeStep(buildCase(scene), 0.2);
    const Stopwatch settleClock;
    Simulation settling(buildCase(scene), dt);
    while (settling.world().time < p.settleTime) settling.step();
    const double rho = bulkDensity(settling.world(), p, kind.size);
    c.note("  silo " + kind.name + ": " + std::to_string(p.grains) + " grains, packed in " +
           roundedText(packed.seconds, 3) + " s wall, dt " +
           numberText(dt) + " s, settled in " + roundedText(settleClock.seconds(), 3) +
           " s wall; bulk density " + roundedText(rho, 4) + " t/mm³");

    const std::string name = "silo " + kind.name;
    std::vector<Discharge> flows;
    Series curves{"silo_" + kind.name + "_discharge", {"orifice", "time", "mass"}, {}};
    // Largest orifice first: the quickest discharge reports first (each starts from a copy of
    // the same settled fill, so the order changes no result).
    for (auto it = p.orifices.rbegin(); it != p.orifices.rend(); ++it) {
        const double orifice = *it;
        const bool frames = orifice == p.orifices.back() && p.frames > 0;
        const Stopwatch runClock;
        DischargeRun run = discharge(settling.world(), p, orifice, dt, kind.size, frames);
        c.note("  silo " + kind.name + " D=" + numberText(orifice) + ": " +
               std::to_string(run.times.size()) + " grains out in " +
               roundedText(run.times.empty() ? 0.0 : run.times.back(), 3) + " s" +
               (run.clogged ? " (clogged)" : ", steady flow " +
                                                  roundedText(run.steady.slope, 4) + " t/s") +
               ", " + roundedText(runClock.seconds(), 3) + " s wall");
        addDischargeChecks(c, name + " D=" + numberText(orifice), p, run);
        for (size_t k = 0; k < run.times.size(); k += 10)
            curves.rows.push_back({orifice, run.times[k], run.masses[k]});
        if (run.clogged) continue;
        flows.push_back({orifice, run.steady.slope});
        if (frames) c.report.frames.push_back({"silo_" + kind.name, std::move(run.frames)});
    }
    Series rates{"silo_" + kind.name, {"orifice", "mass_flow", "bulk_density", "grain_size"}, {}};
    std::sort(flows.begin(), flows.end(),
              [](const Discharge& a, const Discharge& b) { return a.diameter < b.diameter; });
    for (const Discharge& f : flows) rates.rows.push_back({f.diameter, f.massFlow, rho, kind.size});
    c.report.series.push_back(rates);
    c.report.series.push_back(curves);
    if (flows.size() >= 2) addBeverlooChecks(c, name, flows, rho, p.gravity, kind.size,
                                           2.0 * p.siloRadius);
}

} // namespace

void siloDischarge(Context& c)
{
    const SiloPlan p = planAsAsked(c.quick, c.siloRadius, c.siloHeight, c.siloOrifices);
    if (wantsKind(c.siloGrains, "spheres")) runKind(c, p, spheres(c, c.quick));
    // (The quick version leaves the sand out: its packing alone takes minutes.)
    if (wantsKind(c.siloGrains, "sand") && !c.quick) runKind(c, p, sand(c));
}

} // namespace lsdem::verify

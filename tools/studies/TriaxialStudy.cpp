#include "studies/TriaxialStudy.h"

#include "studies/TriaxialMembrane.h"

#include "studies/TriaxialCost.h"

#include "lsdem/core/NumberText.h"
#include "studies/RunDistributor.h"
#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"
#include "studies/TriaxialSample.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <initializer_list>

namespace lsdem {

namespace {

constexpr int kRowFields = 25;

void packRow(const TriaxialRow& r, std::vector<double>& out)
{
    const TriaxialState& s = r.state;
    const double fields[kRowFields] = {
        double(r.stage), double(r.step), r.time, s.size.x(), s.size.y(), s.size.z(), s.volume,
        s.stress.x(), s.stress.y(), s.stress.z(), s.p, s.q, s.voidRatio, s.coordination,
        r.axialStrain, r.volumetricStrain, r.frictionAngle, r.inertialNumber, r.kinetic,
        s.loveWeberStress.x(), s.loveWeberStress.y(), s.loveWeberStress.z(),
        s.mechanicalCoordination, s.fabricAnisotropy, s.nodesPerContact};
    out.insert(out.end(), fields, fields + kRowFields);
}

TriaxialRow unpackRow(const double* f)
{
    TriaxialRow r;
    r.stage = int(f[0]);
    r.step = static_cast<long long>(f[1]);
    r.time = f[2];
    r.state.size = Vec3(f[3], f[4], f[5]);
    r.state.volume = f[6];
    r.state.stress = Vec3(f[7], f[8], f[9]);
    r.state.p = f[10];
    r.state.q = f[11];
    r.state.voidRatio = f[12];
    r.state.coordination = f[13];
    r.axialStrain = f[14];
    r.volumetricStrain = f[15];
    r.frictionAngle = f[16];
    r.inertialNumber = f[17];
    r.kinetic = f[18];
    r.state.loveWeberStress = Vec3(f[19], f[20], f[21]);
    r.state.mechanicalCoordination = f[22];
    r.state.fabricAnisotropy = f[23];
    r.state.nodesPerContact = f[24];
    return r;
}

std::string encodeRun(const TriaxialRun& r)
{
    ByteWriter<> w;
    w.text(formulationName(r.formulation));
    w.integer(r.seed);
    w.number(r.sdp).number(r.vdp).number(r.nodesPerGrain).number(r.stiffness).number(r.dt);
    w.number(r.stabilityLimit);
    w.number(r.strainRate).number(r.bakeSeconds).number(r.runSeconds).number(r.msPerStep);
    const TriaxialTestResult& t = r.test;
    w.integer(t.consolidatedWithinTolerance ? 1 : 0);
    w.integer(t.consolidationSteps).integer(t.shearSteps);
    w.number(t.shearSeconds).number(t.shearSecondsEstimate);
    w.text(triaxialPathName(r.path)).number(t.unloadReloadModulus);
    std::vector<double> consolidated, rows;
    packRow(TriaxialRow{1, 0, 0.0, t.consolidated}, consolidated);
    for (const TriaxialRow& row : t.rows) packRow(row, rows);
    w.numbers(consolidated).numbers(rows);
    std::vector<double> poses, wallPoints;
    for (const RigidPose& pose : t.consolidatedPoses) {
        poses.insert(poses.end(), pose.position.data(), pose.position.data() + 3);
        poses.insert(poses.end(), pose.orientation.coeffs().data(),
                     pose.orientation.coeffs().data() + 4);
    }
    for (const Vec3& point : t.consolidatedWallPoints)
        wallPoints.insert(wallPoints.end(), point.data(), point.data() + 3);
    w.numbers(poses).numbers(wallPoints);
    // In a membrane: the grains kept, the tube and its vertices.
    std::vector<double> kept(t.consolidatedGrains.begin(), t.consolidatedGrains.end()), tube,
        vertices;
    const MembraneSpec& m = t.consolidatedTube;
    tube = {m.rubber.youngs, m.rubber.poisson, m.rubber.thickness, m.rubber.density, m.pressure,
            m.drag, m.base.x(), m.base.y(), m.base.z(), m.axis.x(), m.axis.y(), m.axis.z(),
            m.radius, m.height, double(m.segments), double(m.rings), m.prestretch};
    for (const Vec3& x : t.consolidatedMembrane) vertices.insert(vertices.end(), x.data(), x.data() + 3);
    w.numbers(kept).numbers(tube).numbers(vertices);
    return w.bytes();
}

TriaxialRun decodeRun(const std::string& bytes, double maxAxialStrain)
{
    ByteReader in(bytes);
    TriaxialRun r;
    r.formulation = parseFormulation(in.text());
    r.seed = in.integer();
    r.sdp = in.number();
    r.vdp = in.number();
    r.nodesPerGrain = in.number();
    r.stiffness = in.number();
    r.dt = in.number();
    r.stabilityLimit = in.number();
    r.strainRate = in.number();
    r.bakeSeconds = in.number();
    r.runSeconds = in.number();
    r.msPerStep = in.number();
    r.test.consolidatedWithinTolerance = in.integer() != 0;
    r.test.consolidationSteps = in.integer();
    r.test.shearSteps = in.integer();
    r.test.shearSeconds = in.number();
    r.test.shearSecondsEstimate = in.number();
    r.path = triaxialPathNamed(in.text()).value_or(TriaxialPath::Compression);
    r.test.unloadReloadModulus = in.number();
    r.test.consolidated = unpackRow(in.numbers().data()).state;
    const std::vector<double> rows = in.numbers();
    for (size_t k = 0; k + kRowFields <= rows.size(); k += kRowFields)
        r.test.rows.push_back(unpackRow(rows.data() + k));
    const std::vector<double> poses = in.numbers(), wallPoints = in.numbers();
    for (size_t k = 0; k + 7 <= poses.size(); k += 7) {
        RigidPose pose;
        pose.position = Vec3(poses[k], poses[k + 1], poses[k + 2]);
        pose.orientation.coeffs() = Eigen::Vector4d(poses[k + 3], poses[k + 4], poses[k + 5], poses[k + 6]);
        r.test.consolidatedPoses.push_back(pose);
    }
    for (size_t k = 0; k < 6 && 3 * k + 2 < wallPoints.size(); ++k)
        r.test.consolidatedWallPoints[k] = Vec3(wallPoints[3 * k], wallPoints[3 * k + 1], wallPoints[3 * k + 2]);
    const std::vector<double> kept = in.numbers(), tube = in.numbers(), vertices = in.numbers();
    for (double i : kept) r.test.consolidatedGrains.push_back(static_cast<long long>(i));
    if (tube.size() == 17) {
        MembraneSpec& m = r.test.consolidatedTube;
        m.rubber = MembraneMaterial{tube[0], tube[1], tube[2], tube[3]};
        m.pressure = tube[4];
        m.drag = tube[5];
        m.base = Vec3(tube[6], tube[7], tube[8]);
        m.axis = Vec3(tube[9], tube[10], tube[11]);
        m.radius = tube[12];
        m.height = tube[13];
        m.segments = int(tube[14]);
        m.rings = int(tube[15]);
        m.prestretch = tube[16];
    }
    for (size_t k = 0; k + 2 < vertices.size(); k += 3)
        r.test.consolidatedMembrane.push_back(Vec3(vertices[k], vertices[k + 1], vertices[k + 2]));
    summariseTriaxialShearing(r.test, maxAxialStrain);
    return r;
}

/// A step well inside the stability limit of a grain pressed by σ₃ on all sides: a contact of
/// two spheres of the mean diameter d carrying σ₃·d² has k = 2·sqrt(π·k*·(d/4)·F) (the adapted
/// law's F = π·k*·R·δ²; original acts like k* = kn / node area), about ten such contacts press
/// a grain, and half the limit 2·sqrt(m/k) leaves room for the peaks (the 27-grain sample saw
/// a limit 3 times this step). Never above the stable step of the stiffest contact a grain can
/// make (automaticTimeStep at safety 1; the stability check guards the rest).
double triaxialTimeStep(const World& world, const TriaxialOptions& o, Formulation f,
                        const TriaxialAssets& a, double kn)
{
    const double kStar = *normalModel(f).tractionStiffness(kn, a.meanNodeArea);
    const double d = a.meanDiameter;
    const double force = o.confiningStress * d * d;
    const double contact = 2.0 * std::sqrt(kPi * kStar * 0.25 * d * force);
    double lightest = 1e300;
    for (const Grain& g : world.grains) lightest = std::min(lightest, g.body.mass);
    const double estimate = 0.5 * 2.0 * std::sqrt(lightest / (10.0 * contact));
    return std::min(estimate, automaticTimeStep(world, 1.0));
}

/// Refuse to report @a run if its figures went NaN or inf, or its cell is impossible (walls
/// crossed, a negative void ratio): absurd scales of the options, not a result.
void refuseNonPhysicalRun(const TriaxialRun& run)
{
    auto finite = [](std::initializer_list<double> figures) {
        return std::all_of(figures.begin(), figures.end(),
                           [](double v) { return std::isfinite(v); });
    };
    const TriaxialTestResult& t = run.test;
    std::string wrong;
    auto check = [&](const TriaxialState& s, const char* when, bool rowFinite) {
        if (!wrong.empty()) return;
        if (!rowFinite || !s.size.allFinite() || !s.stress.allFinite() ||
            !finite({s.volume, s.p, s.q, s.voidRatio, s.coordination}))
            wrong = std::string("went non-finite (NaN or inf) ") + when;
        else if (!(s.size.minCoeff() > 0.0 && s.voidRatio >= 0.0))
            wrong = std::string("became impossible ") + when + ": cell " +
                    roundedText(s.size.x()) + " x " + roundedText(s.size.y()) + " x " +
                    roundedText(s.size.z()) + " mm, void ratio " + roundedText(s.voidRatio);
    };
    check(t.consolidated, "when consolidated", true);
    for (const TriaxialRow& r : t.rows)
        check(r.state, r.stage == 0 ? "while consolidating" : "while shearing",
              finite({r.axialStrain, r.volumetricStrain, r.frictionAngle, r.inertialNumber,
                      r.kinetic}));
    if (wrong.empty() && !finite({t.peakFrictionAngle, t.peakAxialStrain, t.criticalFrictionAngle,
                                  t.criticalVoidRatio, t.maxInertialNumber, t.secantModulus50}))
        wrong = "went non-finite (NaN or inf) in its summary";
    if (wrong.empty()) return;
    throw Error("", "the triaxial run of " + formulationName(run.formulation) + " at SDP " +
                        roundedText(run.sdp) + " mm " + wrong,
                "check the scales and units of the options (mm, tonne, s, N, MPa): "
                "--confining-stress, --density, --kn-star, --lattice-spacing, --inertial-number");
}

/// A run set up and not yet stepped: its assets, world, time step and protocol.
struct PlannedRun
{
    TriaxialRun run;  ///< what is known before it is stepped
    World world;
    TriaxialProtocol protocol;
    long long shearSteps = 0;
};

/// Bake (or reuse) the assets of a run, build the cloud, its scene and world, and choose the
/// time step: all but the stepping, which is what a run and the study's estimate share.
PlannedRun planRun(const TriaxialOptions& o, const std::vector<std::string>& files, Formulation f,
                   double sdp, long long seed, double spacing, double kn)
{
    const std::shared_ptr<const TriaxialAssets> assets = sharedTriaxialAssets(files, o.vdp, sdp);
    PlannedRun plan;
    TriaxialRun& run = plan.run;
    run.formulation = f;
    run.sdp = sdp;
    run.seed = seed;
    run.vdp = o.vdp;
    run.nodesPerGrain = assets->meanNodes;
    run.stiffness = kn;
    run.bakeSeconds = assets->bakeSeconds;
    run.strainRate = triaxialStrainRate(o, assets->meanDiameter);
    run.path = o.path;

    TriaxialProtocol& p = plan.protocol;
    p.confiningStress = o.confiningStress;
    p.strainRate = run.strainRate;
    p.consolidationRate = 10.0 * run.strainRate;
    p.maxAxialStrain = o.maxAxialStrain;
    p.stressTolerance = o.stressTolerance;
    p.friction = o.friction;
    p.consolidationFriction = o.consolidationFriction;
    p.grainDiameter = assets->meanDiameter;
    p.density = o.density;
    p.records = o.records;
    p.path = o.path;
    p.b = o.b;
    p.unloadStrain = o.unloadStrain;
    p.cycles = o.cycles;

    if (!(spacing > 2.0 * assets->largestBoundingRadius))
        throw Error("", "the lattice spacing " + roundedText(spacing) + " mm is not more than "
                            "the largest bounding diameter " +
                            roundedText(2.0 * assets->largestBoundingRadius) +
                            " mm of the grains at SDP " + roundedText(sdp) + ": they would overlap",
                    "leave --lattice-spacing at 0 (derived), or give a larger one");
    const TriaxialCloud cloud =
        makeTriaxialCloud(o.grains, int(assets->assets.size()), spacing,
                          static_cast<std::uint64_t>(seed), o.heightRatio);
    const Scene scene = triaxialScene(o, *assets, cloud, f, kn);
    std::vector<std::string> warnings;
    plan.world = buildWorld(scene, warnings);
    run.dt = triaxialTimeStep(plan.world, o, f, *assets, kn);
    // A plan too long is refused now, not retried with half the step.
    plan.shearSteps = triaxialShearSteps(p, run.dt);
    return plan;
}

/// Say on stderr why a run's step @a dt is halved while @a stage (its time and its results
/// change with it, and a step that keeps failing is then the run's error).
void tellHalvedStep(const char* stage, double dt, const Error& why)
{
    std::fprintf(stderr, "  step %.3g s halved while %s: %s\n", dt, stage, why.what());
}

/// The shearing of @a consolidated (a copy of the simulation's world once consolidated, and the
/// test so far), again with half the step each time @a first's step proves unstable: the
/// consolidation is kept, not done again. The first try shears on @a first (the consolidating
/// simulation itself, so a run that needs no second try steps exactly as before). @a dt ends
/// as the step that sheared, @a stabilityLimit as the least limit any try saw.
TriaxialTestResult shearWithSteadyStep(Simulation& first, const World& consolidated,
                                       const TriaxialTestResult& test, const TriaxialWalls& walls,
                                       const TriaxialProtocol& p, double& dt,
                                       double& stabilityLimit,
                                       const std::function<void(const TriaxialRow&)>& progress)
{
    for (int attempt = 0;; ++attempt) {
        TriaxialTestResult result = test;
        try {
            if (attempt == 0) {
                shearTriaxial(first, walls, p, result, progress);
            } else {
                Simulation again(consolidated, dt);
                try {
                    shearTriaxial(again, walls, p, result, progress);
                } catch (const Error&) {
                    stabilityLimit = std::min(stabilityLimit, again.stabilityLimitSeen());
                    throw;
                }
                stabilityLimit = std::min(stabilityLimit, again.stabilityLimitSeen());
            }
            stabilityLimit = std::min(stabilityLimit, first.stabilityLimitSeen());
            return result;
        } catch (const Error& e) {
            if (attempt >= 3) throw;  // not a matter of the step
            tellHalvedStep("shearing", dt, e);
            dt *= 0.5;
        }
    }
}

/// --boundary membrane: the sample consolidated between walls (@a between) cut into a cylinder
/// and wrapped in a membrane (TriaxialMembrane.h), which @a sim then runs, consolidated again
/// under the cell pressure and the platens' servo. Its rows follow the walls' (both stage 0);
/// @a walls becomes the platens and the membrane.
TriaxialTestResult consolidateInMembrane(const TriaxialOptions& o,
                                         const std::vector<std::string>& files,
                                         const PlannedRun& plan,
                                         std::optional<Simulation>& sim,
                                         const TriaxialTestResult& between, double dt,
                                         TriaxialWalls& walls,
                                         const std::function<void(const TriaxialRow&)>& progress)
{
    const std::shared_ptr<const TriaxialAssets> assets =
        sharedTriaxialAssets(files, o.vdp, plan.run.sdp);
    const bool perArea = normalModel(plan.run.formulation).stiffnessPerArea();
    const double stiffnessPerArea =
        perArea ? plan.run.stiffness : plan.run.stiffness / assets->meanNodeArea;
    // Its density set for the planned step: a step halved on a retry then has room to spare.
    TriaxialMembraneSample sample = wrapInMembrane(sim->world(), walls, o, assets->meanDiameter,
                                                   plan.run.dt, stiffnessPerArea,
                                                   plan.run.strainRate);
    std::printf("  %s SDP %g: membrane round %zu grains (%lld cut off), radius %.3g mm, "
                "t %.3g mm, %zu triangles, its mass %.3g times the grains'\n",
                formulationName(plan.run.formulation).c_str(), plan.run.sdp,
                sample.world.grains.size(), sample.grainsCut, sample.radius,
                sample.world.membranes[0].rubber.thickness,
                sample.world.membranes[0].triangles.size(), sample.massRatio);
    walls = sample.walls;
    sim.emplace(std::move(sample.world), dt);
    TriaxialTestResult inMembrane = consolidateTriaxial(*sim, walls, plan.protocol, progress);
    inMembrane.consolidatedGrains = sample.kept;
    inMembrane.consolidatedTube = sample.tube;
    const Membrane& consolidatedMembrane = sim->world().membranes[0];
    inMembrane.consolidatedTube.pressure = consolidatedMembrane.pressure;  // as steered
    inMembrane.consolidatedMembrane = consolidatedMembrane.positions;
    inMembrane.rows.insert(inMembrane.rows.begin(), between.rows.begin(), between.rows.end());
    inMembrane.consolidationSteps += between.consolidationSteps;
    return inMembrane;
}

/// One run: planned, consolidated and sheared. A step the simulation finds unstable while
/// consolidating is halved and the run started again; while shearing, halved and the shearing
/// started again from the consolidated sample (shearWithSteadyStep).
TriaxialRun runOne(const TriaxialOptions& o, const std::vector<std::string>& files,
                   Formulation f, double sdp, long long seed, double spacing, double kn,
                   const std::function<void(const TriaxialRow&)>& progress)
{
    PlannedRun plan = planRun(o, files, f, sdp, seed, spacing, kn);
    TriaxialRun& run = plan.run;
    const TriaxialWalls walls = o.periodic ? periodicTriaxialCell() : triaxialWalls();
    double dt = run.dt;
    const Stopwatch runClock;
    for (int attempt = 0;; ++attempt) {
        std::optional<Simulation> sim;
        TriaxialTestResult consolidated;
        TriaxialWalls shearWalls = walls;
        try {
            sim.emplace(plan.world, dt);
            triaxialShearSteps(plan.protocol, dt);  // refused before consolidating
            consolidated = consolidateTriaxial(*sim, walls, plan.protocol, progress);
            if (o.membrane) consolidated = consolidateInMembrane(o, files, plan, sim, consolidated,
                                                                 dt, shearWalls, progress);
        } catch (const Error& e) {
            if (attempt >= 3) throw;  // not a matter of the step
            tellHalvedStep("consolidating", dt, e);
            dt *= 0.5;
            continue;
        }
        // The shearing has its own tries (from the consolidated sample): an error it gives up
        // on is the run's.
        const World afterConsolidation = sim->world();
        double limit = std::numeric_limits<double>::infinity();
        run.test = shearWithSteadyStep(*sim, afterConsolidation, consolidated, shearWalls,
                                       plan.protocol, dt, limit, progress);
        run.stabilityLimit = limit;
        break;
    }
    run.dt = dt;
    run.runSeconds = runClock.seconds();
    const long long steps = run.test.consolidationSteps + run.test.shearSteps;
    run.msPerStep = steps > 0 ? 1e3 * run.runSeconds / double(steps) : 0.0;
    refuseNonPhysicalRun(run);
    return run;
}

/// What the estimate needs of run @a plan, named @a name.
TriaxialRunPlan costPlanOf(const PlannedRun& plan, const TriaxialOptions& o, std::string name)
{
    TriaxialRunPlan c;
    c.name = std::move(name);
    c.grains = o.grains;
    c.nodesPerGrain = plan.run.nodesPerGrain;
    c.timeStep = plan.run.dt;
    c.startVoidRatio =
        measureTriaxialCell(plan.world, o.periodic ? periodicTriaxialCell() : triaxialWalls(), {})
            .voidRatio;
    c.approachRate = plan.protocol.approachRate;
    c.settledSteps = plan.protocol.settledSteps;
    c.shearSteps = plan.shearSteps;
    c.membrane = o.membrane;
    c.heightRatio = o.heightRatio;
    return c;
}

} // namespace

double triaxialStrainRate(const TriaxialOptions& o, double meanDiameter)
{
    return o.inertialNumber / (meanDiameter * std::sqrt(o.density / o.confiningStress));
}

TriaxialStudyResult runTriaxialStudy(
    const TriaxialOptions& o, RunDistributor& ranks,
    const std::function<void(const TriaxialRun&)>& onRun,
    const std::function<void(Formulation, double, long long, const TriaxialRow&)>& progress,
    const std::function<void(const std::vector<TriaxialRunPlan>&)>& onPlan)
{
    checkTriaxialOptions(o);
    const std::vector<std::string> files = triaxialMeshFiles(o);
    // A run is described by its formulation, SDP, seed, the lattice spacing and the
    // stiffness: the rest is in the options every rank has.
    const RunDistributor::Job job = [&](const std::string& description) {
        ByteReader in(description);
        const Formulation f = parseFormulation(in.text());
        const double sdp = in.number();
        const long long seed = in.integer();
        const double spacing = in.number(), kn = in.number();
        std::function<void(const TriaxialRow&)> tell;
        if (progress && ranks.isRoot())
            tell = [&](const TriaxialRow& row) { progress(f, sdp, seed, row); };
        return encodeRun(runOne(o, files, f, sdp, seed, spacing, kn, tell));
    };
    if (!ranks.isRoot()) {
        ranks.serve(job);
        return {};
    }

    // The coarsest assets set the lattice (every run starts from the same grains in the same
    // places) and original's kn (the same law as adapted's there).
    const std::shared_ptr<const TriaxialAssets> coarsest = sharedTriaxialAssets(files, o.vdp, o.sdps.front());
    TriaxialStudyResult result;
    result.meshes = int(files.size());
    result.grains = o.grains;
    result.spacing = o.latticeSpacing > 0.0 ? o.latticeSpacing : triaxialCloudSpacing(*coarsest);
    result.meanDiameter = coarsest->meanDiameter;
    // Each law's stiffness: kn* for the laws per area; the others' acts like kn* on the
    // coarsest nodes unless --kn-original gives it.
    auto stiffnessOf = [&](Formulation f) {
        const NormalModel& law = normalModel(f);
        if (law.stiffnessPerArea()) return o.knStar;
        return o.knOriginal > 0.0 ? o.knOriginal
                                  : *law.stiffnessForTraction(o.knStar, coarsest->meanNodeArea);
    };

    std::vector<std::string> descriptions;
    std::vector<TriaxialRunPlan> plans;
    // Every seed's sample on the lattice of the coarsest assets (the lattice's spacing does
    // not depend on the seed, only which mesh and orientation each site gets). Each run is
    // planned here (its assets baked, its world built, its step chosen) for the estimate.
    for (Formulation f : o.formulations)
        for (double sdp : o.sdps)
            for (long long seed : o.seeds) {
                ByteWriter<> w;
                w.text(formulationName(f)).number(sdp).integer(seed).number(result.spacing);
                w.number(stiffnessOf(f));
                descriptions.push_back(w.bytes());
                char name[80];
                std::snprintf(name, sizeof name, "%s SDP %g seed %lld", formulationName(f).c_str(),
                              sdp, seed);
                plans.push_back(costPlanOf(
                    planRun(o, files, f, sdp, seed, result.spacing, stiffnessOf(f)), o, name));
            }
    if (onPlan) onPlan(plans);
    if (o.estimateOnly) {  // the plans were all it asked for
        ranks.finish();
        return result;
    }
    // The runs handed out largest first, by the estimate (threads alike on every rank).
    std::vector<double> costs;
    for (const TriaxialRunPlan& p : plans) costs.push_back(triaxialRunCost(p, 2).seconds);
    result.runs.resize(descriptions.size());
    ranks.runAll(descriptions, costs, job, [&](size_t index, int, const std::string& bytes) {
        result.runs[index] = decodeRun(bytes, o.maxAxialStrain);
        if (onRun) onRun(result.runs[index]);
    });
    ranks.finish();
    return result;
}

} // namespace lsdem

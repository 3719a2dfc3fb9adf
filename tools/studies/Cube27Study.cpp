#include "studies/Cube27Study.h"

#include "lsdem/scene/BuildWorld.h"
#include "lsdem/ls/Constants.h"
#include "lsdem/scene/RandomRotation.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/simulation/World.h"
#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/AtomicFile.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/Error.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <tuple>

namespace lsdem {

namespace {

/// δ = kColumn·d_w for a column of wall, two sphere–sphere contacts and floor.
const double kColumn = 2.0 + 2.0 * std::sqrt(2.0);
/// Throughput measured on the development machine (2 shared cores, 0.9–1.7e8 from N = 16000
/// down to 500) for the cost estimate printed before a study: grain-node steps per second.
constexpr double kNodeStepsPerSecond = 1.2e8;

double baseStiffness(Formulation f)
{
    return (f == Formulation::Original || f == Formulation::SingleNode) ? 1e9 : 1e3;
}

/// A uniformly random rotation drawn from @a rng (the studies' reproducible sequence).
Quat randomRotation(std::mt19937& rng)
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    return lsdem::randomRotation([&] { return u(rng); });
}

/// Contact stiffnesses of a column at top wall travel @a delta, from the continuum laws:
/// kWall (sphere against a plane) and kSphere (sphere against sphere), force/length.
struct ColumnStiffness
{
    double kWall = 0.0, kSphere = 0.0;
};

ColumnStiffness columnStiffness(Formulation f, double radius, double delta, double stiffness,
                                int nodes)
{
    ColumnStiffness c;
    if (f == Formulation::SingleNode) {
        // One linear spring per contact (symmetric testing: two half-weight deepest nodes).
        c.kWall = c.kSphere = stiffness;
        return c;
    }
    const double kStar = f == Formulation::Original
                             ? originalEffectiveStiffness(stiffness, nodes, 4 * kPi * radius * radius)
                             : stiffness;
    const double dWall = delta / kColumn, dSphere = std::sqrt(2.0) * dWall;
    c.kWall = 2 * kPi * kStar * radius * dWall;     // d/dd of π k R d²
    c.kSphere = kPi * kStar * radius * dSphere;     // d/dδ of (π/2) k R δ²
    return c;
}

bool hasShear(const Cube27Options& o, Formulation f)
{
    return (f == Formulation::Original || f == Formulation::Adapted) && o.friction > 0 &&
           o.shearRatio > 0;
}

std::string formatNumber(double v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", v);
    return buffer;
}

/// A baked asset in a temporary file, removed when the guard dies.
class TemporaryAsset
{
public:
    TemporaryAsset(const GrainAsset& asset, int nodes)
    {
        static int counter = 0;
        mPath = (std::filesystem::temp_directory_path() /
                 ("lsdem-cube27-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
                  "-" + std::to_string(nodes) + ".vdb"))
                    .string();
        saveAsset(asset, mPath);
    }
    ~TemporaryAsset()
    {
        std::error_code ec;
        std::filesystem::remove(mPath, ec);
    }
    TemporaryAsset(const TemporaryAsset&) = delete;
    TemporaryAsset& operator=(const TemporaryAsset&) = delete;
    const std::string& path() const { return mPath; }

private:
    std::string mPath;
};

/// What one run recorded at each δ sample.
struct Samples
{
    std::vector<double> delta, top, floor, side;
};

} // namespace

Cube27Options cube27FullOptions()
{
    Cube27Options o;
    o.nodeCounts = {500, 1000, 2000, 4000, 8000, 16000};
    o.orientations = 3;
    o.voxel = 0.05;
    return o;
}

void checkCube27Options(const Cube27Options& o)
{
    checkSphereSeriesOptions(o);
    auto positive = [](double v, const std::string& option, const std::string& example) {
        if (!(v > 0.0) || !std::isfinite(v))
            throw Error("", option + " must be positive and finite", "e.g. " + option + " " + example);
    };
    if (o.deltaMax >= 0.5 * o.radius)
        throw Error("", "--delta-max must be smaller than half the radius",
                    "the closed form and the stack assume small overlaps; e.g. --delta-max 0.3");
    if (o.voxel > 0.25 * o.radius)
        throw Error("", "--voxel is too coarse for the radius (more than R/4)", "e.g. --voxel 0.1");
    if (o.speed < 0.0 || !std::isfinite(o.speed))
        throw Error("", "--speed must be positive (or 0 for the automatic speed)", "e.g. --speed 20");
    if (o.steps < 0 || o.steps > 100000000)
        throw Error("", "--steps must be 1 to 1e8 (or 0 for the automatic count)");
    positive(o.periods, "--periods", "30");
    if (!(o.safety > 0.0 && o.safety <= 1.0))
        throw Error("", "--safety must be in (0, 1]", "e.g. --safety 0.2");
    if (o.points < 1 || o.points > 100000) throw Error("", "--points must be 1 to 100000");
    positive(o.density, "density", "7.85e-9");
    if (o.friction < 0.0 || !std::isfinite(o.friction)) throw Error("", "--friction must be >= 0");
    if (o.shearRatio < 0.0 || !std::isfinite(o.shearRatio))
        throw Error("", "--shear-ratio must be >= 0");
    if (!(o.restitution > 0.0 && o.restitution <= 1.0))
        throw Error("", "--restitution must be in (0, 1]", "e.g. --restitution 0.5");
    if (!(o.globalDamping >= 0.0 && o.globalDamping < 1.0))
        throw Error("", "--damping must be in [0, 1)", "e.g. --damping 0.3");
}

double cube27ClosedForm(double radius, double delta, double knStar)
{
    if (delta <= 0.0) return 0.0;
    return 9.0 * kPi * knStar * radius * delta * delta / (kColumn * kColumn);
}

double cube27ExactForce(double radius, double delta, double knStar)
{
    if (delta <= 0.0) return 0.0;
    // The force is linear in k at fixed geometry: solve with k = 1 and scale. Both unknowns
    // solve equations that are nearly linear (sqrt of the sphere force in the overlap, the
    // column travel in d_w), so secant iterations from the parabolic solution converge in a
    // few steps.
    auto secant = [](const auto& f, double x0, double x1) {
        double f0 = f(x0), f1 = f(x1);
        for (int i = 0; i < 60 && f1 != f0; ++i) {
            const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
            x0 = x1;
            f0 = f1;
            x1 = x2;
            f1 = f(x1);
            if (std::abs(x1 - x0) <= 1e-14 * std::abs(x1)) break;
        }
        return x1;
    };
    auto travel = [&](double dWall) {
        const double force = kPi * radius * dWall * dWall;  // sphere–plane, exact
        const double dSphere = secant(
            [&](double d) { return std::sqrt(exactSphereContactForce(radius, d, 1.0)) - std::sqrt(force); },
            std::sqrt(2.0) * dWall, 1.01 * std::sqrt(2.0) * dWall);
        return 2.0 * dWall + 2.0 * dSphere;
    };
    const double dWall =
        secant([&](double d) { return travel(d) - delta; }, delta / kColumn, 0.99 * delta / kColumn);
    return 9.0 * kPi * knStar * radius * dWall * dWall;
}

double originalEffectiveStiffness(double kn, double nodes, double area)
{
    return kn * nodes / area;
}

Cube27Run planCube27Run(const Cube27Options& o, Formulation f, int nodes, double stiffness,
                        int orientation)
{
    Cube27Run run;
    run.formulation = f;
    run.nodes = nodes;
    run.stiffness = stiffness;
    run.orientation = orientation;

    const double mass = o.density * 4.0 / 3.0 * kPi * std::pow(o.radius, 3);
    const double inertia = 0.4 * mass * o.radius * o.radius;
    const ColumnStiffness c = columnStiffness(f, o.radius, o.deltaMax, stiffness, nodes);
    // Stiffest grain: the top (or bottom) sphere, a wall on one side and a sphere on the other;
    // the middle one has two sphere contacts.
    const double kGrain = std::max(c.kWall + c.kSphere, 2.0 * c.kSphere);
    double omegaMax2 = kGrain / mass;
    if (hasShear(o, f))  // rotation on the shear springs at distance R
        omegaMax2 = std::max(omegaMax2, o.shearRatio * kGrain * o.radius * o.radius / inertia);
    run.stabilityLimit = 2.0 / std::sqrt(omegaMax2);
    // Slowest vertical mode of a column (symmetric mode of wall–m–m–m–floor).
    const double trace = c.kWall + 3.0 * c.kSphere, det = 2.0 * c.kWall * c.kSphere;
    const double omega1 = std::sqrt((trace - std::sqrt(trace * trace - 4.0 * det)) / 2.0 / mass);
    const double loadingTime =
        o.speed > 0.0 ? o.deltaMax / o.speed : o.periods * 2.0 * kPi / omega1;

    if (o.steps > 0) {
        run.steps = o.steps;
        run.timeStep = loadingTime / double(o.steps);
        if (run.timeStep > run.stabilityLimit) {
            std::ostringstream s;
            s << "--steps " << o.steps << " is too few for " << formulationName(f) << " at N = "
              << nodes << ", k = " << stiffness << ": the time step " << run.timeStep
              << " s would exceed the stack's stability limit " << run.stabilityLimit << " s";
            throw Error("", s.str(),
                        "give at least --steps " +
                            std::to_string((long long)std::ceil(loadingTime / run.stabilityLimit)) +
                            " (5x that is safe), or leave --steps out");
        }
    } else {
        const double dt = o.safety * run.stabilityLimit;
        run.steps = std::max<long long>(1, (long long)std::ceil(loadingTime / dt));
        run.timeStep = loadingTime / double(run.steps);
    }
    run.speed = o.deltaMax / (run.timeStep * double(run.steps));
    return run;
}

std::vector<Cube27Run> planCube27(const Cube27Options& o)
{
    checkCube27Options(o);
    const int kSeriesCount = stiffnessSeriesNodes(o);
    std::vector<Cube27Run> runs;
    for (int nodes : o.nodeCounts)
        for (Formulation f : o.formulations) {
            std::vector<double> ks;
            if (!o.stiffness.empty()) ks = o.stiffness;
            else if (nodes == kSeriesCount)
                for (double factor : o.stiffnessFactors) ks.push_back(factor * baseStiffness(f));
            else ks.push_back(baseStiffness(f));
            for (double k : ks)
                for (int m = 0; m < o.orientations; ++m)
                    runs.push_back(planCube27Run(o, f, nodes, k, m));
        }
    return runs;
}

Scene makeCube27Scene(const Cube27Options& o, const Cube27Run& run, const std::string& assetFile)
{
    const double r = o.radius, side = 6.0 * r;
    Scene scene;
    scene.path = "(lsdem-study cube27)";
    AssetSpec asset;
    asset.name = "sphere";
    if (assetFile.empty()) {
        asset.shape = AnalyticShape::sphere(r);
        asset.bake.voxelSize = o.voxel;
        asset.bake.nodePlacement = NodePlacement::Count;
        asset.bake.nodeCount = run.nodes;
    } else {
        asset.file = assetFile;
    }
    asset.where = scene.path;
    scene.assets.push_back(asset);
    scene.materials.push_back({"steel", o.density});
    scene.materials.push_back({"wall", 0.0});

    ContactModel model;
    model.formulation = run.formulation;
    model.testing = o.testing;
    model.normalStiffness = run.stiffness;
    model.shearStiffness = o.shearRatio * run.stiffness;
    model.friction = o.friction;
    for (int other : {0, 1}) {
        ContactSpec c;
        c.materialA = 0;
        c.materialB = other;
        c.model = model;
        c.restitution = o.restitution;
        c.where = scene.path;
        scene.contacts.push_back(c);
    }

    // The orientation set: one random rotation per grain, the same set for every N and law.
    std::mt19937 rng(o.seed * 7919u + unsigned(run.orientation));
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                GrainSpec g;
                g.name = "sphere_" + std::to_string(i) + std::to_string(j) + std::to_string(k);
                g.asset = 0;
                g.material = 0;
                g.pose.position = Vec3((2 * i + 1) * r, (2 * j + 1) * r, (2 * k + 1) * r);
                g.pose.orientation = randomRotation(rng);
                g.where = scene.path;
                scene.grains.push_back(g);
            }

    auto wall = [&](const std::string& name, const Vec3& point, const Vec3& normal) {
        BoundarySpec b;
        b.name = name;
        b.shape = BoundaryShape::Plane;
        b.material = 1;
        b.point = point;
        b.normal = normal;
        b.where = scene.path;
        scene.boundaries.push_back(b);
    };
    wall("floor", Vec3(0, 0, 0), Vec3::UnitZ());
    wall("top", Vec3(0, 0, side), -Vec3::UnitZ());
    wall("west", Vec3(0, 0, 0), Vec3::UnitX());
    wall("east", Vec3(side, 0, 0), -Vec3::UnitX());
    wall("south", Vec3(0, 0, 0), Vec3::UnitY());
    wall("north", Vec3(0, side, 0), -Vec3::UnitY());
    scene.boundaries[1].velocity = Vec3(0, 0, -run.speed);

    scene.gravity = Vec3::Zero();
    scene.globalDamping = o.globalDamping;
    scene.timeStep.fixed = run.timeStep;
    scene.end.boundary = 1;
    scene.end.displacement = o.deltaMax;
    scene.end.steps = run.steps;
    return scene;
}

Cube27Result runCube27(const Cube27Options& o)
{
    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point t) {
        return std::chrono::duration<double>(Clock::now() - t).count();
    };
    checkCube27Options(o);
    Cube27Result result;
    result.runs = planCube27(o);

    double totalNodeSteps = 0.0;
    for (const Cube27Run& run : result.runs) totalNodeSteps += 27.0 * run.nodes * double(run.steps);
    if (!o.quiet) {
        std::printf("cube27 plan: %zu runs (27 grains each); cost = grains x nodes x steps\n",
                    result.runs.size());
        std::printf("  %-11s %6s %9s %3s %10s %8s %10s %10s\n", "formulation", "N", "k", "m",
                    "dt [s]", "steps", "v [mm/s]", "node-steps");
        for (const Cube27Run& run : result.runs)
            std::printf("  %-11s %6d %9.3g %3d %10.3g %8lld %10.3g %10.3g\n",
                        formulationName(run.formulation).c_str(), run.nodes, run.stiffness,
                        run.orientation, run.timeStep, run.steps, run.speed,
                        27.0 * run.nodes * double(run.steps));
        std::printf("  total %.3g node-steps, about %.0f s at %.2g node-steps/s (2 cores)\n",
                    totalNodeSteps, totalNodeSteps / kNodeStepsPerSecond, kNodeStepsPerSecond);
        std::fflush(stdout);
    }

    // Samples per run, grouped by (formulation, N, k) in plan order.
    using Key = std::tuple<int, int, double>;
    std::map<Key, std::vector<Samples>> samples;
    std::map<int, double> nodesActual;
    std::vector<Key> order;
    double doneNodeSteps = 0.0;
    size_t index = 0;
    for (int nodes : o.nodeCounts) {
        const auto bakeStart = Clock::now();
        std::vector<std::string> warnings;
        const GrainAsset sphere = bakeSeriesSphere(o, nodes, warnings);
        const TemporaryAsset file(sphere, nodes);
        nodesActual[nodes] = double(sphere.nodes.size());
        result.bakeSeconds += since(bakeStart);
        if (!o.quiet) {
            std::printf("N = %d: baked %zu nodes (spacing %.3g mm), voxel %g mm\n", nodes,
                        sphere.nodes.size(), sphere.spacing.mean, o.voxel);
            for (const std::string& w : warnings) std::printf("  warning: %s\n", w.c_str());
        }

        for (; index < result.runs.size() && result.runs[index].nodes == nodes; ++index) {
            Cube27Run& run = result.runs[index];
            const auto start = Clock::now();
            const Scene scene = makeCube27Scene(o, run, file.path());
            World world = buildWorld(scene, warnings);
            Samples s;
            auto record = [&](const World& w) {
                const std::vector<Boundary>& b = w.boundaries;
                s.delta.push_back(-b[1].displacement.z());
                s.top.push_back(b[1].force.z());
                s.floor.push_back(-b[0].force.z());
                s.side.push_back(std::abs(b[2].force.x()) + std::abs(b[3].force.x()) +
                                 std::abs(b[4].force.y()) + std::abs(b[5].force.y()));
            };
            try {
                Simulation sim(std::move(world), run.timeStep);
                record(sim.world());
                // δ samples evenly spread over the steps (never more samples than steps).
                const long long points = std::min<long long>(o.points, run.steps);
                long long next = 1;
                for (long long step = 1; step <= run.steps; ++step) {
                    sim.step();
                    if (next <= points && step == (next * run.steps + points / 2) / points) {
                        record(sim.world());
                        ++next;
                    }
                }
                run.stabilityLimitSeen = sim.stabilityLimitSeen();
                run.contactNodes = sim.contactNodes();
            } catch (const Error& e) {
                std::ostringstream where;
                where << formulationName(run.formulation) << " N = " << nodes
                      << " k = " << run.stiffness << " orientation " << run.orientation;
                throw Error("", "cube27 run " + where.str() + ": " + e.problem(),
                            "lower --safety or raise --steps");
            }
            run.seconds = since(start);
            result.simulateSeconds += run.seconds;
            doneNodeSteps += 27.0 * nodes * double(run.steps);
            if (!o.quiet) {
                const double rate = doneNodeSteps / std::max(result.simulateSeconds, 1e-9);
                std::printf("  [%zu/%zu] %-8s N=%-6d k=%-8s m=%d: %lld steps, %.2f s; "
                            "P(δmax) = %.5g N; stability margin %.1fx; ETA %.0f s\n",
                            index + 1, result.runs.size(), formulationName(run.formulation).c_str(),
                            nodes, formatNumber(run.stiffness).c_str(), run.orientation, run.steps,
                            run.seconds, s.top.back(), run.stabilityLimitSeen / run.timeStep,
                            (totalNodeSteps - doneNodeSteps) / rate);
                std::fflush(stdout);
            }
            const Key key{int(run.formulation), nodes, run.stiffness};
            if (!samples.count(key)) order.push_back(key);
            samples[key].push_back(std::move(s));
        }
    }

    // The exact column force per unit stiffness, once per δ (the runs share their δ values).
    std::map<double, double> exactUnit;
    auto exact = [&](double delta, double k) {
        auto it = exactUnit.find(delta);
        if (it == exactUnit.end())
            it = exactUnit.emplace(delta, cube27ExactForce(o.radius, delta, 1.0)).first;
        return k * it->second;
    };
    for (const Key& key : order) {
        const std::vector<Samples>& runs = samples[key];
        const auto [formulation, nodes, stiffness] = key;
        const size_t count = runs.front().delta.size();
        for (size_t i = 0; i < count; ++i) {
            Cube27Row row;
            row.formulation = Formulation(formulation);
            row.nodesRequested = nodes;
            row.nodesActual = nodesActual[nodes];
            row.stiffness = stiffness;
            double sum = 0, sum2 = 0, delta = 0, floor = 0, side = 0;
            row.forceMin = row.forceMax = runs.front().top[i];
            for (const Samples& s : runs) {
                const double p = s.top[i];
                sum += p;
                sum2 += p * p;
                row.forceMin = std::min(row.forceMin, p);
                row.forceMax = std::max(row.forceMax, p);
                delta += s.delta[i];
                floor += s.floor[i];
                side += s.side[i];
            }
            const double n = double(runs.size());
            row.delta = delta / n;
            row.forceMean = sum / n;
            row.forceStd = std::sqrt(std::max(0.0, sum2 / n - row.forceMean * row.forceMean));
            row.floorForce = floor / n;
            row.sideForce = side / n;
            double kStar = stiffness;
            if (row.formulation == Formulation::Original)
                kStar = originalEffectiveStiffness(stiffness, row.nodesActual,
                                                   4 * kPi * o.radius * o.radius);
            if (row.formulation == Formulation::SingleNode) {
                // Linear springs kn in every contact: d_s = d_w = δ/4, 9 columns.
                row.forceClosed = row.forceExact = 9.0 * stiffness * row.delta / 4.0;
            } else {
                row.forceClosed = cube27ClosedForm(o.radius, row.delta, kStar);
                row.forceExact = exact(row.delta, kStar);
            }
            result.rows.push_back(row);
        }
    }
    return result;
}

void writeCube27Csv(const Cube27Result& result, const Cube27Options& o, const std::string& path)
{
    std::ostringstream csv;
    csv.precision(10);
    csv << "# lsdem cube27 study: 27 spheres R=" << o.radius << " mm in [0," << 6 * o.radius
        << "]^3, voxel=" << o.voxel << " mm, testing=" << nodeTestingName(o.testing)
        << ", orientations=" << o.orientations << ", friction=" << o.friction
        << ", ks/kn=" << o.shearRatio << ", restitution=" << o.restitution
        << ", global damping=" << o.globalDamping << ", no gravity\n";
    csv << "# P: reaction on the top wall (mean over orientations), P_floor: on the floor, "
           "P_side: sum of |normal reaction| on the side walls; force in N, lengths in mm\n";
    csv << "# P_closed: 9 pi k R delta^2/(2+2 sqrt 2)^2 (continuum, parabolic caps); P_exact: "
           "the same with exact sphere-sphere caps; k is kn* for adapted/volume and "
           "kn*N/(4 pi R^2) for original; single-node: 9 kn delta/4\n";
    csv << "formulation,nodes,nodes_actual,kn,voxel,delta,P,P_std,P_min,P_max,P_floor,P_side,"
           "P_closed,P_exact\n";
    for (const Cube27Row& r : result.rows)
        csv << formulationName(r.formulation) << ',' << r.nodesRequested << ',' << r.nodesActual
            << ',' << r.stiffness << ',' << o.voxel << ',' << r.delta << ',' << r.forceMean << ','
            << r.forceStd << ',' << r.forceMin << ',' << r.forceMax << ',' << r.floorForce << ','
            << r.sideForce << ',' << r.forceClosed << ',' << r.forceExact << '\n';
    writeTextFileAtomically(path, csv.str());
}

} // namespace lsdem

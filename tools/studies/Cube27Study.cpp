#include "studies/Cube27Study.h"

#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"
#include "studies/RunSchedule.h"
#include "studies/SphereBakeCost.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <tuple>

namespace lsdem {

namespace {

/// Throughput measured on the development machine (2 shared cores) for the cost estimate
/// printed before a study: grain-node steps per second. Most nodes are culled by their blocks
/// before any level-set lookup, so it is far above the cost per sampled node: the default
/// study's 6.1e9 node-steps took 5.2 s on 2026-11-28 (1.2e9/s; 1.2e8 before the node blocks).
constexpr double kNodeStepsPerSecond = 1.0e9;

std::string formatNumber(double v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", v);
    return buffer;
}

/// What one run recorded at each δ sample.
struct Samples
{
    std::vector<double> delta, top, floor, side;
};

/// The plan, printed before the first run: what each run costs and the total.
void printPlan(const Cube27Options& o, const std::vector<Cube27Run>& runs, double totalNodeSteps,
               int ranks, const std::vector<double>& costs)
{
    std::printf("cube27 plan: %zu runs (27 grains each); cost = grains x nodes x steps\n",
                runs.size());
    std::printf("  %-11s %6s %9s %3s %10s %8s %10s %10s\n", "formulation", "N", "k", "m",
                "dt [s]", "steps", "v [mm/s]", "node-steps");
    for (const Cube27Run& run : runs)
        std::printf("  %-11s %6d %9.3g %3d %10.3g %8lld %10.3g %10.3g\n",
                    formulationName(run.formulation).c_str(), run.nodes, run.stiffness,
                    run.orientation, run.timeStep, run.steps, run.speed,
                    27.0 * run.nodes * double(run.steps));
    // Each node count's sphere is baked once (once per rank that runs it under MPI).
    std::set<int> counts;
    for (const Cube27Run& run : runs) counts.insert(run.nodes);
    double bake = 0.0;
    for (int nodes : counts) bake += sphereBakeSeconds(o.radius, o.voxel, nodes);
    const double simulate = totalNodeSteps / kNodeStepsPerSecond;
    std::printf("  total %.3g node-steps: about %.0f s on 2 cores (%.0f s of runs at %.2g "
                "node-steps/s, %.0f s to bake %zu spheres)\n",
                totalNodeSteps, simulate + bake, simulate, kNodeStepsPerSecond, bake, counts.size());
    if (ranks > 1)
        std::printf("  on %d ranks, largest runs first: about %.0f s if each rank has 2 cores, and "
                    "the bakes\n",
                    ranks, largestFirstMakespan(costs, ranks) / kNodeStepsPerSecond);
    std::fflush(stdout);
}

/// Build the scene of @a run with the baked @a sphere, step it through the loading and record
/// the walls at o.points evenly spread steps (and at the start).
Samples simulateRun(const Cube27Options& o, Cube27Run& run,
                    const std::shared_ptr<const GrainAsset>& sphere)
{
    const Scene scene = makeCube27Scene(o, run, sphere);
    std::vector<std::string> warnings;
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
        where << formulationName(run.formulation) << " N = " << run.nodes
              << " k = " << run.stiffness << " orientation " << run.orientation;
        throw Error("", "cube27 run " + where.str() + ": " + e.problem(),
                    "lower --safety or raise --steps");
    }
    return s;
}

/// Runs that differ only in orientation: (formulation, N, k).
using Key = std::tuple<int, int, double>;

/// The column forces at unit traction stiffness, by law and δ.
using UnitForces = std::map<std::pair<Formulation, double>, double>;

/// The exact column force of @a law at @a delta for stiffness @a k: k times the force at unit
/// stiffness, kept in @a unitForce (the runs share their δ values, each costs quadratures).
double exactColumnForce(const Cube27Options& o, Formulation law, double delta, double k,
                        UnitForces& unitForce)
{
    auto it = unitForce.find({law, delta});
    if (it == unitForce.end())
        it = unitForce.emplace(std::pair(law, delta), cube27ExactForce(o.radius, delta, 1.0, law))
                 .first;
    return k * it->second;
}

/// Refuse to report @a row if a figure went NaN or inf (absurd scales: a δ_max that rounds to 0,
/// a stiffness that overflows), and at δ_max (@a last) if P/P_exact, what the study is about,
/// is not a number.
void refuseNonFiniteRow(const Cube27Row& r, bool last)
{
    const double figures[] = {r.delta, r.forceMean, r.forceStd, r.forceMin, r.forceMax,
                              r.floorForce, r.sideForce, r.forceClosed, r.forceExact};
    const bool finite = std::all_of(std::begin(figures), std::end(figures),
                                    [](double v) { return std::isfinite(v); });
    const double relative = r.forceMean / r.forceExact - 1.0;
    if (finite && (!last || std::isfinite(relative))) return;
    std::ostringstream s;
    s << "the cube27 runs of " << formulationName(r.formulation) << " at N = " << r.nodesRequested
      << ", k = " << r.stiffness << " went non-finite (NaN or inf): at delta = " << r.delta
      << " mm, P = " << r.forceMean << " N, P_exact = " << r.forceExact << " N";
    if (finite) s << ", P/P_exact - 1 = " << relative;
    throw Error("", s.str(),
                "check the scales and units of the options (mm, N, s, tonne): --delta-max, "
                "--radius, --kn / --k-factors, --speed");
}

/// Rows of results for one (formulation, N, k): per δ sample, the statistics over the
/// orientations of @a runs and the closed-form and exact references.
void appendRows(const Cube27Options& o, const Key& key, const std::vector<Samples>& runs,
                double nodesActual, UnitForces& unitForce,
                std::vector<Cube27Row>& rows)
{
    const auto [formulation, nodes, stiffness] = key;
    const size_t count = runs.front().delta.size();
    for (size_t i = 0; i < count; ++i) {
        Cube27Row row;
        row.formulation = Formulation(formulation);
        row.nodesRequested = nodes;
        row.nodesActual = nodesActual;
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
        // The law's traction on nodes spread evenly over the sphere (kn·N/(4πR²) for original).
        const std::optional<double> kStar = normalModel(row.formulation)
                                                .tractionStiffness(stiffness, 4 * kPi * o.radius * o.radius /
                                                                                  row.nodesActual);
        if (!kStar) {
            // A law without a traction (single-node): linear springs kn in every contact,
            // d_s = d_w = δ/4, 9 columns.
            row.forceClosed = row.forceExact = 9.0 * stiffness * row.delta / 4.0;
        } else {
            row.forceClosed = cube27ClosedForm(o.radius, row.delta, *kStar);
            row.forceExact = exactColumnForce(o, row.formulation, row.delta, *kStar, unitForce);
        }
        refuseNonFiniteRow(row, i + 1 == count);
        rows.push_back(row);
    }
}

} // namespace

namespace {

/// One run of the plan, on any rank, as a record for rank 0: the sphere of its node count
/// baked (or the one kept: under MPI a rank keeps the spheres it baked, tens of MB each, so
/// each node count is baked once per rank that runs it; serially the plan's order needs one
/// sphere at a time), the stack simulated, its samples and lines.
std::string cube27RunRecord(const Cube27Options& o, const Cube27Run& run, bool live,
                            std::map<int, std::shared_ptr<const GrainAsset>>& spheres)
{
    std::string log;
    double bakeSeconds = 0.0;
    if (live && !spheres.count(run.nodes)) spheres.clear();
    std::shared_ptr<const GrainAsset>& sphere = spheres[run.nodes];
    if (!sphere) {
        const auto bakeStart = SteadyClock::now();
        std::vector<std::string> warnings;
        sphere = std::make_shared<const GrainAsset>(bakeSeriesSphere(o, run.nodes, warnings));
        bakeSeconds = secondsSince(bakeStart);
        if (!o.quiet) {
            char line[160];
            std::snprintf(line, sizeof line, "N = %d: baked %zu nodes (spacing %.3g mm), voxel %g mm\n",
                          run.nodes, sphere->nodes.size(), sphere->spacing.mean, o.voxel);
            log += line;
            for (const std::string& w : warnings) log += "  warning: " + w + "\n";
        }
        if (live) {
            std::fputs(log.c_str(), stdout);
            log.clear();
        }
    }
    Cube27Run done = run;
    const auto start = SteadyClock::now();
    const Samples s = simulateRun(o, done, sphere);
    ByteWriter<> out;
    out.number(secondsSince(start)).number(done.stabilityLimitSeen).integer(done.contactNodes);
    out.number(double(sphere->nodes.size())).number(bakeSeconds);
    out.numbers(s.delta).numbers(s.top).numbers(s.floor).numbers(s.side).text(log);
    return out.bytes();
}

/// The line of a run done: its rank's lines, the run, and the time left at the rate so far
/// (node-steps per second of one rank, the time left shared among the ranks).
void printRunDone(const std::string& log, size_t done, size_t runs, const Cube27Run& run,
                  const Samples& s, double rate, double nodeStepsLeft, int ranks, int rank)
{
    std::printf("%s  [%zu/%zu] %-8s N=%-6d k=%-8s m=%d: %lld steps, %.2f s; "
                "P(δmax) = %.5g N; stability margin %.1fx; ETA %.0f s",
                log.c_str(), done, runs, formulationName(run.formulation).c_str(), run.nodes,
                formatNumber(run.stiffness).c_str(), run.orientation, run.steps, run.seconds,
                s.top.back(), run.stabilityLimitSeen / run.timeStep, nodeStepsLeft / rate / ranks);
    if (ranks > 1) std::printf(" (rank %d)", rank);
    std::printf("\n");
    std::fflush(stdout);
}

/// The result's rows, grouped by (formulation, N, k) in plan order, wherever each run was done.
void appendGroupedRows(const Cube27Options& o, Cube27Result& result, std::vector<Samples>& samplesOf,
                       std::map<int, double>& nodesActual)
{
    std::map<Key, std::vector<Samples>> samples;
    std::vector<Key> order;
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const Cube27Run& run = result.runs[i];
        const Key key{int(run.formulation), run.nodes, run.stiffness};
        if (!samples.count(key)) order.push_back(key);
        samples[key].push_back(std::move(samplesOf[i]));
    }
    UnitForces unitForce;
    for (const Key& key : order)
        appendRows(o, key, samples[key], nodesActual[std::get<1>(key)], unitForce, result.rows);
}

} // namespace

Cube27Result runCube27(const Cube27Options& o, RunDistributor& ranks)
{
    checkCube27Options(o);
    Cube27Result result;
    result.runs = planCube27(o);
    const bool live = ranks.ranks() == 1;
    std::map<int, std::shared_ptr<const GrainAsset>> spheres;
    const RunDistributor::Job job = [&](const std::string& description) {
        return cube27RunRecord(o, result.runs.at(size_t(ByteReader(description).integer())), live,
                               spheres);
    };
    if (!ranks.isRoot()) {
        ranks.serve(job);
        return {};
    }

    double totalNodeSteps = 0.0;
    std::vector<std::string> descriptions;
    std::vector<double> costs;
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const Cube27Run& run = result.runs[i];
        costs.push_back(27.0 * run.nodes * double(run.steps));
        totalNodeSteps += costs.back();
        descriptions.push_back(ByteWriter<>().integer(static_cast<long long>(i)).bytes());
    }
    if (!o.quiet) printPlan(o, result.runs, totalNodeSteps, ranks.ranks(), costs);

    std::vector<Samples> samplesOf(result.runs.size());
    std::map<int, double> nodesActual;
    double doneNodeSteps = 0.0;
    size_t done = 0;
    RunShares shares(ranks.ranks());
    ranks.runAll(descriptions, costs, job, [&](size_t index, int rank, const std::string& record) {
        Cube27Run& run = result.runs[index];
        ByteReader in(record);
        run.seconds = in.number();
        run.stabilityLimitSeen = in.number();
        run.contactNodes = in.integer();
        nodesActual[run.nodes] = in.number();
        result.bakeSeconds += in.number();
        Samples& s = samplesOf[index];
        s.delta = in.numbers();
        s.top = in.numbers();
        s.floor = in.numbers();
        s.side = in.numbers();
        const std::string log = in.text();
        result.simulateSeconds += run.seconds;
        doneNodeSteps += costs[index];
        shares.add(rank);
        ++done;
        if (!o.quiet)
            printRunDone(log, done, result.runs.size(), run, s,
                         doneNodeSteps / std::max(result.simulateSeconds, 1e-9),
                         totalNodeSteps - doneNodeSteps, ranks.ranks(), rank);
    });
    ranks.finish();
    if (!live) std::printf("%s\n", shares.text().c_str());
    appendGroupedRows(o, result, samplesOf, nodesActual);
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
           "the same with exact sphere-sphere caps (for volume: kv times the caps' integral of d); "
           "k is kn* for adapted/volume and "
           "kn*N/(4 pi R^2) for original; single-node: 9 kn delta/4\n";
    csv << "# kn_unit: the unit of kn; converges: 1 if the law converges to P_exact as the nodes "
           "refine at a fixed kn\n";
    csv << "formulation,nodes,nodes_actual,kn,voxel,delta,P,P_std,P_min,P_max,P_floor,P_side,"
           "P_closed,P_exact,kn_unit,converges\n";
    for (const Cube27Row& r : result.rows) {
        const NormalModel& law = normalModel(r.formulation);
        csv << formulationName(r.formulation) << ',' << r.nodesRequested << ',' << r.nodesActual
            << ',' << r.stiffness << ',' << o.voxel << ',' << r.delta << ',' << r.forceMean << ','
            << r.forceStd << ',' << r.forceMin << ',' << r.forceMax << ',' << r.floorForce << ','
            << r.sideForce << ',' << r.forceClosed << ',' << r.forceExact << ','
            << law.stiffnessUnitIn("N", "mm") << ',' << (law.convergesWithNodes() ? 1 : 0)
            << '\n';
    }
    writeTextFileAtomically(path, csv.str());
}

} // namespace lsdem

#include "studies/TwoSpheresStudy.h"

#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"
#include "studies/RunSchedule.h"
#include "studies/SphereBakeCost.h"

#include "lsdem/contact/PairContact.h"
#include "lsdem/scene/RandomRotation.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/Stopwatch.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace lsdem {

double defaultStiffness(Formulation f) { return normalModel(f).paperStiffness(); }

void checkTwoSpheresOptions(const TwoSpheresOptions& o)
{
    checkSphereSeriesOptions(o);
    if (o.deltaMax >= o.radius)
        throw Error("", "--delta-max must be smaller than the radius (spheres would pass through)");
    if (o.steps < 1 || o.steps > 100000) throw Error("", "--steps must be 1 to 100000");
}

namespace {

struct Series
{
    Formulation formulation;
    double stiffness;
};

/// The series of node count @a nodes: each law at every --stiffness given, else at its
/// paper's stiffness times each factor at the stiffness series' node count, else at its
/// paper's stiffness alone.
std::vector<Series> seriesAt(const TwoSpheresOptions& o, int nodes)
{
    const int kSeriesCount = stiffnessSeriesNodes(o);
    std::vector<Series> series;
    for (Formulation f : o.formulations) {
        if (!o.stiffness.empty()) {
            for (double k : o.stiffness) series.push_back({f, k});
        } else if (nodes == kSeriesCount) {
            for (double factor : o.stiffnessFactors)
                series.push_back({f, factor * defaultStiffness(f)});
        } else {
            series.push_back({f, defaultStiffness(f)});
        }
    }
    return series;
}

/// The force P[series][step][orientation] along the centre line, on two copies of @a sphere
/// turned at random (one set of turns per orientation), pressed together step by step.
std::vector<std::vector<std::vector<double>>> centreLineForces(const TwoSpheresOptions& o,
                                                               const GrainAsset& sphere,
                                                               const std::vector<Series>& series,
                                                               NodeCheckStats& stats)
{
    std::vector<std::vector<std::vector<double>>> force(
        series.size(), std::vector<std::vector<double>>(o.steps + 1));
    for (int m = 0; m < o.orientations; ++m) {
        std::mt19937_64 rng(o.seed * 7919u + unsigned(m));
        ContactGrain fixed, moved;
        fixed.asset = moved.asset = &sphere;
        fixed.index = 0;
        moved.index = 1;
        fixed.pose.orientation = randomRotation(rng);
        moved.pose.orientation = randomRotation(rng);
        for (int step = 0; step <= o.steps; ++step) {
            const double delta = o.deltaMax * step / o.steps;
            moved.pose.position = Vec3(2 * o.radius - delta, 0, 0);
            for (size_t s = 0; s < series.size(); ++s) {
                ContactModel model;
                model.formulation = series[s].formulation;
                model.normalStiffness = series[s].stiffness;
                model.testing = o.testing;
                const PairForces f = computePairContact(fixed, moved, model, 0.0, nullptr, stats);
                force[s][step].push_back(f.forceOnSecond.x());  // along the centre line
            }
        }
    }
    return force;
}

/// The row of one series and step: @a p, the force over the orientations, as its mean,
/// spread, least and largest, beside the law's continuum limit.
TwoSpheresRow forceRow(const TwoSpheresOptions& o, const Series& series, int nodes,
                       const GrainAsset& sphere, int step, const std::vector<double>& p)
{
    TwoSpheresRow row;
    row.formulation = series.formulation;
    row.nodesRequested = nodes;
    row.nodesActual = double(sphere.nodes.size());
    row.stiffness = series.stiffness;
    row.delta = o.deltaMax * step / o.steps;
    double sum = 0, sum2 = 0;
    row.forceMin = p.front();
    row.forceMax = p.front();
    for (double v : p) {
        sum += v;
        sum2 += v * v;
        row.forceMin = std::min(row.forceMin, v);
        row.forceMax = std::max(row.forceMax, v);
    }
    row.forceMean = sum / p.size();
    row.forceStd = std::sqrt(std::max(0.0, sum2 / p.size() - row.forceMean * row.forceMean));
    // Each law's continuum limit at its stiffness taken as a traction: the limit of
    // the laws per area (SCIENCE.md §3); for the others, what the adapted law would
    // give at the same number (they diverge from it as the nodes refine).
    row.forceExact =
        normalModel(row.formulation).continuumSphereForce(o.radius, row.delta, row.stiffness);
    return row;
}

/// One node count of the study (bake, every series and orientation) into @a part; its
/// progress line goes to stdout if @a live, else into @a log.
void runNodeCount(const TwoSpheresOptions& o, int nodes, bool live, TwoSpheresResult& part,
                  std::string& log)
{
    const Stopwatch bake;
    std::vector<std::string> warnings;
    const GrainAsset sphere = bakeSeriesSphere(o, nodes, warnings);
    part.bakeSeconds += bake.seconds();
    const Stopwatch contact;
    if (!o.quiet) {
        char line[160];
        std::snprintf(line, sizeof line, "  N = %d: baked %zu nodes (spacing %.4g mm)\n", nodes,
                      sphere.nodes.size(), sphere.spacing.mean);
        if (live)
            std::fputs(line, stdout);
        else
            log += line;
    }
    const std::vector<Series> series = seriesAt(o, nodes);
    const auto force = centreLineForces(o, sphere, series, part.stats);
    for (size_t s = 0; s < series.size(); ++s)
        for (int step = 0; step <= o.steps; ++step)
            part.rows.push_back(forceRow(o, series[s], nodes, sphere, step, force[s][step]));
    part.contactSeconds += contact.seconds();
}

/// A node count's part of the result as a run record, and back.
std::string partRecord(const TwoSpheresResult& part, const std::string& log)
{
    ByteWriter<> out;
    out.integer(static_cast<long long>(part.rows.size()));
    for (const TwoSpheresRow& r : part.rows)
        out.integer(static_cast<long long>(r.formulation))
            .integer(r.nodesRequested)
            .number(r.nodesActual)
            .number(r.stiffness)
            .number(r.delta)
            .number(r.forceMean)
            .number(r.forceStd)
            .number(r.forceMin)
            .number(r.forceMax)
            .number(r.forceExact);
    const NodeCheckStats& s = part.stats;
    out.integer(s.nodesConsidered).integer(s.nodesCulled).integer(s.nodesSampled).integer(s.nodesInContact);
    out.integer(s.nodesPassedOver);
    out.number(part.bakeSeconds).number(part.contactSeconds).text(log);
    return out.bytes();
}

/// The part in @a record into @a part; returns its progress text.
std::string readPartRecord(const std::string& record, TwoSpheresResult& part)
{
    ByteReader in(record);
    for (long long n = in.integer(); n > 0; --n) {
        TwoSpheresRow r;
        r.formulation = Formulation(in.integer());
        r.nodesRequested = int(in.integer());
        r.nodesActual = in.number();
        r.stiffness = in.number();
        r.delta = in.number();
        r.forceMean = in.number();
        r.forceStd = in.number();
        r.forceMin = in.number();
        r.forceMax = in.number();
        r.forceExact = in.number();
        part.rows.push_back(r);
    }
    NodeCheckStats& s = part.stats;
    s.nodesConsidered = in.integer();
    s.nodesCulled = in.integer();
    s.nodesSampled = in.integer();
    s.nodesInContact = in.integer();
    s.nodesPassedOver = in.integer();
    part.bakeSeconds = in.number();
    part.contactSeconds = in.number();
    return in.text();
}

} // namespace

double twoSpheresRunSeconds(const TwoSpheresOptions& o, int nodes)
{
    const size_t series = seriesAt(o, nodes).size();
    // Each contact evaluation considers every node of both spheres (symmetric testing; one
    // way half) and culls nearly all by their blocks: 1.8e9 nodes a second measured here
    // (the default study, 2026-11-29), a rounding error beside the bake.
    const double sides = o.testing == NodeTesting::Symmetric ? 2.0 : 1.0;
    const double considered = sides * nodes * double(series) * o.orientations * (o.steps + 1);
    return sphereBakeSeconds(o.radius, o.voxel, nodes) + considered / 1.8e9;
}

std::string twoSpheresPlanText(const TwoSpheresOptions& o, int ranks)
{
    std::vector<double> costs;
    double seconds = 0.0;
    for (int nodes : o.nodeCounts) {
        costs.push_back(twoSpheresRunSeconds(o, nodes));
        seconds += costs.back();
    }
    std::ostringstream t;
    t.precision(2);
    t << "two-spheres plan: " << o.nodeCounts.size() << " spheres baked (voxel " << o.voxel
      << " mm, up to " << *std::max_element(o.nodeCounts.begin(), o.nodeCounts.end())
      << " nodes), each pressed " << o.steps << " steps in " << o.orientations
      << " orientations; about " << seconds << " s on 2 cores";
    if (ranks > 1)
        t << ", " << largestFirstMakespan(costs, ranks) << " s on " << ranks
          << " ranks of 2 cores";
    return t.str();
}

TwoSpheresResult runTwoSpheres(const TwoSpheresOptions& o, RunDistributor& ranks)
{
    checkTwoSpheresOptions(o);
    const bool live = ranks.ranks() == 1;
    // One run per node count: its bake, every series and orientation.
    const RunDistributor::Job job = [&](const std::string& description) {
        const int nodes = o.nodeCounts.at(size_t(ByteReader(description).integer()));
        TwoSpheresResult part;
        std::string log;
        runNodeCount(o, nodes, live, part, log);
        return partRecord(part, log);
    };
    if (!ranks.isRoot()) {
        ranks.serve(job);
        return {};
    }

    std::vector<std::string> descriptions;
    std::vector<double> costs;
    for (size_t i = 0; i < o.nodeCounts.size(); ++i) {
        descriptions.push_back(ByteWriter<>().integer(static_cast<long long>(i)).bytes());
        costs.push_back(twoSpheresRunSeconds(o, o.nodeCounts[i]));
    }
    std::vector<TwoSpheresResult> parts(descriptions.size());
    RunShares shares(ranks.ranks());
    ranks.runAll(descriptions, costs, job, [&](size_t i, int rank, const std::string& record) {
        shares.add(rank);
        std::printf("%s", readPartRecord(record, parts[i]).c_str());
        std::fflush(stdout);
    });
    ranks.finish();

    TwoSpheresResult result;  // in the order of the node counts, wherever each was run
    for (const TwoSpheresResult& part : parts) {
        result.rows.insert(result.rows.end(), part.rows.begin(), part.rows.end());
        result.stats += part.stats;
        result.bakeSeconds += part.bakeSeconds;
        result.contactSeconds += part.contactSeconds;
    }
    if (ranks.ranks() > 1) std::printf("%s\n", shares.text().c_str());
    return result;
}

void writeTwoSpheresCsv(const TwoSpheresResult& result, const TwoSpheresOptions& o,
                        const std::string& path)
{
    std::ostringstream csv;
    csv.precision(10);
    csv << "# lsdem two-spheres study: R=" << o.radius << " mm, voxel=" << o.voxel
        << " mm, testing=" << nodeTestingName(o.testing) << ", orientations=" << o.orientations
        << "; force in N, lengths in mm; P_exact is the adapted formulation's continuum limit "
           "for the row's stiffness (for volume rows the volume law's, kv times the cap's "
           "integral of d); kn_unit: the unit of kn; converges: 1 if the law converges to "
           "P_exact as the nodes refine\n";
    csv << "formulation,nodes,nodes_actual,kn,voxel,delta,P,P_std,P_min,P_max,P_exact,kn_unit,"
           "converges\n";
    for (const TwoSpheresRow& r : result.rows) {
        const NormalModel& law = normalModel(r.formulation);
        csv << formulationName(r.formulation) << ',' << r.nodesRequested << ',' << r.nodesActual
            << ',' << r.stiffness << ',' << o.voxel << ',' << r.delta << ',' << r.forceMean << ','
            << r.forceStd << ',' << r.forceMin << ',' << r.forceMax << ',' << r.forceExact << ','
            << law.stiffnessUnitIn("N", "mm") << ',' << (law.convergesWithNodes() ? 1 : 0)
            << '\n';
    }
    writeTextFileAtomically(path, csv.str());
}

} // namespace lsdem

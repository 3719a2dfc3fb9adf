#include "studies/TwoSpheresStudy.h"

#include "lsdem/contact/PairContact.h"
#include "lsdem/scene/RandomRotation.h"
#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/ls/AtomicFile.h"
#include "lsdem/ls/Error.h"
#include "lsdem/ls/Stopwatch.h"

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

} // namespace

TwoSpheresResult runTwoSpheres(const TwoSpheresOptions& o)
{
    checkTwoSpheresOptions(o);
    TwoSpheresResult result;
    const int kSeriesCount = stiffnessSeriesNodes(o);

    for (int nodes : o.nodeCounts) {
        const Stopwatch bake;
        std::vector<std::string> warnings;
        const GrainAsset sphere = bakeSeriesSphere(o, nodes, warnings);
        result.bakeSeconds += bake.seconds();
        const Stopwatch contact;
        if (!o.quiet)
            std::printf("  N = %d: baked %zu nodes (spacing %.4g mm)\n", nodes, sphere.nodes.size(),
                        sphere.spacing.mean);

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
        // P[series][step][orientation]
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
                    const PairForces f =
                        computePairContact(fixed, moved, model, 0.0, nullptr, result.stats);
                    force[s][step].push_back(f.forceOnSecond.x());  // along the centre line
                }
            }
        }
        for (size_t s = 0; s < series.size(); ++s)
            for (int step = 0; step <= o.steps; ++step) {
                const std::vector<double>& p = force[s][step];
                TwoSpheresRow row;
                row.formulation = series[s].formulation;
                row.nodesRequested = nodes;
                row.nodesActual = double(sphere.nodes.size());
                row.stiffness = series[s].stiffness;
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
                row.forceExact = exactSphereContactForce(o.radius, row.delta, row.stiffness);
                result.rows.push_back(row);
            }
        result.contactSeconds += contact.seconds();
    }
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
           "for the row's stiffness\n";
    csv << "formulation,nodes,nodes_actual,kn,voxel,delta,P,P_std,P_min,P_max,P_exact\n";
    for (const TwoSpheresRow& r : result.rows)
        csv << formulationName(r.formulation) << ',' << r.nodesRequested << ',' << r.nodesActual
            << ',' << r.stiffness << ',' << o.voxel << ',' << r.delta << ',' << r.forceMean << ','
            << r.forceStd << ',' << r.forceMin << ',' << r.forceMax << ',' << r.forceExact << '\n';
    writeTextFileAtomically(path, csv.str());
}

} // namespace lsdem

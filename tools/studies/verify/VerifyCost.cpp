#include "studies/verify/VerifyCost.h"

#include "studies/SphereBakeCost.h"
#include "studies/verify/VerifyCases.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

namespace lsdem::verify {

namespace {

/// "42 s", "3.4 min", "2.1 h".
std::string duration(double seconds)
{
    char text[32];
    if (seconds < 100.0)
        std::snprintf(text, sizeof text, "%.2g s", seconds);
    else if (seconds < 6000.0)
        std::snprintf(text, sizeof text, "%.2g min", seconds / 60.0);
    else
        std::snprintf(text, sizeof text, "%.2g h", seconds / 3600.0);
    return text;
}

/// A case's seconds with the laws of @a o, full or quick, its laws' runs taking @a lawScale
/// times what they took when measured.
double caseSeconds(const VerifyOptions& o, const CaseCost& cost, double lawScale)
{
    double laws = 0.0;
    const std::vector<Formulation>& every = allFormulations();
    for (size_t i = 0; i < every.size() && i < std::size(cost.perLaw); ++i)
        if (std::find(o.formulations.begin(), o.formulations.end(), every[i]) != o.formulations.end())
            laws += cost.perLaw[i];
    const double seconds = cost.fixed + lawScale * laws;
    return o.quick ? seconds * cost.quickShare : seconds;
}

} // namespace

std::string VerifyEstimate::text() const
{
    std::string t = "about ";
    if (siloMost > siloLeast)
        t += duration(seconds - siloMost + siloLeast) + " to " + duration(seconds);
    else
        t += duration(seconds);
    t += " on 2 cores (";
    for (size_t i = 0; i < parts.size(); ++i)
        t += (i ? ", " : "") + parts[i].name + " " + duration(parts[i].seconds);
    return t + ")";
}

VerifyEstimate estimateVerification(const VerifyOptions& o)
{
    VerifyEstimate e;
    const Setup measured;  // the ball the cases' costs were measured with
    // The ball's runs take about √N: 0.71, 1 and 1.39 times as long at 2000, 4000 and 8000
    // nodes (oblique-wall, original and adapted, 2026-11-29), fewer steps culling more nodes.
    const double ballScale = std::sqrt(double(o.setup.sphereNodes) / double(measured.sphereNodes));
    bool ball = false;
    for (const CaseEntry& entry : caseList()) {
        if (!runsCase(o, entry)) continue;
        const CaseCost& cost = entry.cost;
        double seconds = 0.0;
        if (cost.model) {
            const auto [least, most] = cost.model(o);
            e.siloLeast += least;
            e.siloMost += most;
            seconds = most;
        } else {
            seconds = caseSeconds(o, cost, cost.ball ? ballScale : 1.0);
        }
        ball = ball || cost.ball;
        e.parts.push_back({entry.name, seconds});
    }
    if (ball) {
        const Setup& s = o.setup;
        e.parts.insert(e.parts.begin(),
                       {"the ball's bake", sphereBakeSeconds(s.radius, s.sphereVoxel, s.sphereNodes)});
    }
    for (const VerifyEstimate::Part& p : e.parts) e.seconds += p.seconds;
    return e;
}

} // namespace lsdem::verify

#include "studies/verify/VerifyStudy.h"

#include "studies/verify/VerifyCases.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/core/Stopwatch.h"

#include <algorithm>

namespace lsdem::verify {

bool caseRunsLaw(CaseLaws laws, Formulation f)
{
    switch (laws) {
    case CaseLaws::Every: return true;
    case CaseLaws::Frictional: return normalModel(f).perNodeForces();
    case CaseLaws::Face: return f != Formulation::SingleNode;
    case CaseLaws::Own: return f == Formulation::Adapted;
    }
    return false;
}

std::vector<Formulation> lawsOfCase(const Context& c, CaseLaws laws)
{
    std::vector<Formulation> run;
    for (Formulation f : c.formulations)
        if (caseRunsLaw(laws, f)) run.push_back(f);
    return run;
}

const std::vector<CaseEntry>& caseList()
{
    // The costs: seconds of each case's full version, apart from any law and per law
    // (original, adapted, single-node, volume), on the setup's ball (4000 nodes, voxel 0.1 mm)
    // without its bake, and the quick version's share of that; measured on this machine's 2
    // idle cores (2026-11-29: `lsdem-study verify` with every law and with each alone, and
    // `verify --quick`, each case's time as printed).
    using L = CaseLaws;
    static const std::vector<CaseEntry> cases = {
        {"normal-wall", "Chung & Ooi 2: a ball's normal impact on a wall", normalImpactOnWall,
         L::Every, {0.0, {0.08, 0.08, 0.08, 0.08}, 0.6, true, {}}},
        {"normal-pair", "Chung & Ooi 1: two balls' normal impact", normalImpactOfTwoSpheres,
         L::Every, {0.15, {0.24, 0.24, 0.1, 0.2}, 0.96, true, {}}},
        {"restitution", "Chung & Ooi 3: rebound over restitutions 0.1 … 1", restitutionSweep,
         L::Every, {0.8, {0.2, 0.2, 0.25, 0.3}, 0.23, true, {}}},
        {"oblique-wall", "Chung & Ooi 4: oblique impact on a wall, 5° … 85°", obliqueImpactOnWall,
         L::Frictional, {0.0, {7.6, 25.6, 0.0, 0.0}, 0.053, true, {}}},
        {"oblique-normal-speed", "Chung & Ooi 5: normal speed fixed, tangential swept",
         obliqueImpactAtNormalSpeed, L::Frictional, {0.0, {5.3, 29.7, 0.0, 0.0}, 0.044, true, {}}},
        {"spin-wall", "Chung & Ooi 6: a spinning ball's impact on a wall", spinImpactOnWall,
         L::Frictional, {0.0, {5.5, 55.2, 0.0, 0.0}, 0.037, true, {}}},
        {"spin-pair", "Chung & Ooi 7: two balls spinning oppositely meet: no slip",
         spinImpactOfTwoBalls, L::Frictional, {0.0, {0.1, 0.1, 0.0, 0.0}, 0.15, true, {}}},
        {"spin-heavy-ball", "Chung & Ooi 8: a spinning ball's impact on a heavy ball",
         spinImpactOnHeavyBall, L::Frictional, {0.0, {9.1, 90.6, 0.0, 0.0}, 0.04, true, {}}},
        {"slide-to-roll", "a ball slides, then rolls on at 5/7 of its speed", slideToRollOnAFloor,
         L::Frictional, {12.0, {1.5, 1.5, 0.0, 0.0}, 0.96, true, {}}},
        {"incline", "a box sliding down an incline", boxOnAnIncline, L::Frictional,
         {0.0, {24.0, 24.0, 0.0, 0.0}, 0.094, false, {}}},
        {"box-landing", "a box landing flat: automatic step, restitution", boxLandingFlat, L::Face,
         {0.0, {0.43, 0.42, 0.0, 0.21}, 0.21, false, {}}},
        {"free-rotation", "a box turning over about its intermediate axis", freeRotation, L::Own,
         {0.09, {0.0, 0.0, 0.0, 0.0}, 0.2, false, {}}},
        {"convergence", "the adapted law's errors as the ball's nodes refine, 1000 … 16,000",
         convergence, L::Own, {16.3, {0.0, 0.0, 0.0, 0.0}, 0.44, false, {}}},
        {"silo",
         "a silo emptied through 4 orifices: Beverloo's law, spheres and sand (run when named: "
         "spheres 13-20 min, sand 3-4 h on 2 cores, estimated (--estimate); in --quick, a "
         "small silo of spheres)",
         siloDischarge, L::Own, {0.0, {0.0, 0.0, 0.0, 0.0}, 1.0, false, siloDischargeSeconds},
         true},
    };
    return cases;
}

bool runsCase(const VerifyOptions& o, const CaseEntry& e)
{
    return o.cases.empty() ? !(e.onlyWhenNamed && !o.quick)
                           : std::find(o.cases.begin(), o.cases.end(), e.name) != o.cases.end();
}

void checkVerifyOptions(const VerifyOptions& o)
{
    for (const std::string& name : o.cases) {
        const auto& list = caseList();
        if (std::none_of(list.begin(), list.end(), [&](const CaseEntry& e) { return e.name == name; })) {
            std::string known;
            for (const CaseEntry& e : list) known += (known.empty() ? "" : ", ") + e.name;
            throw Error("", "--case: no case '" + name + "'", "choose from: " + known);
        }
    }
    if (o.formulations.empty())
        throw Error("", "--formulation: no formulation given", "name at least one");
    for (const auto& [option, value] : {std::make_pair("--silo-radius", o.siloRadius),
                                        std::make_pair("--silo-height", o.siloHeight)})
        if (!(value == 0.0 || (value >= 4.0 && value <= 100.0)))
            throw Error("", std::string(option) + ": " + numberText(value) +
                                " mm is outside [4, 100] mm (the grains are 1 mm)",
                        "e.g. --silo-radius 20 --silo-height 40");
    // The silo is 20 mm wide (8 mm in --quick) unless told: Beverloo's premise wants it at
    // least 2.5 orifices wide; an orifice under two grain sizes (1 mm grains) clogs at once.
    const double width = 2.0 * (o.siloRadius > 0.0 ? o.siloRadius : o.quick ? 4.0 : 10.0);
    const double widest = std::floor(width / 2.5 * 1e6) / 1e6;
    for (double d : o.siloOrifices)
        if (!(d >= 2.0 && d <= widest))
            throw Error("", "--silo-orifices: " + numberText(d) + " mm is outside [2, " +
                                numberText(widest) + "] mm",
                        "the silo is " + numberText(width) +
                            " mm wide and its grains 1 mm; e.g. --silo-orifices 5 6");
    if (!(o.setup.sphereNodes >= 100))
        throw Error("", "--nodes must be at least 100 (got " + std::to_string(o.setup.sphereNodes) + ")",
                    "e.g. --nodes 4000");
    if (!(o.setup.sphereVoxel > 0.0) || o.setup.sphereVoxel > 0.1 * o.setup.radius)
        throw Error("", "--voxel must be in (0, R/10] (got " + numberText(o.setup.sphereVoxel) + ")",
                    "e.g. --voxel 0.1");
}

Report runVerification(const VerifyOptions& o,
                       const std::function<void(const std::string&)>& progress)
{
    Report report;
    Bodies bodies(o.setup);
    Context context{bodies,       o.formulations, o.quick,          report,
                    o.sandMeshes, o.siloGrains,    o.siloOrifices, o.siloRadius,
                    o.siloHeight, progress};
    for (const CaseEntry& e : caseList()) {
        if (!runsCase(o, e)) continue;
        context.note("running " + e.name + " ...");
        const Stopwatch clock;
        e.run(context);
        context.note("  " + e.name + ": " + roundedText(clock.seconds(), 3) + " s");
    }
    return report;
}

} // namespace lsdem::verify

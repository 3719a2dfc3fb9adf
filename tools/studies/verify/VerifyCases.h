/// @file VerifyCases.h
/// @brief The cases of the verification suite (docs/verification.md), each adding its checks
///        and figure data to a Report: Chung & Ooi's eight tests at the particle level, rolling,
///        blocks on walls, free rotation, convergence with the node count, and a silo.
#pragma once

#include "studies/verify/VerifyReport.h"
#include "studies/verify/VerifySetup.h"
#include "studies/verify/VerifyStudy.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace lsdem::verify {

struct Context
{
    Bodies& bodies;
    std::vector<Formulation> formulations;  ///< those a case applies to are run
    bool quick = false;                     ///< fewer points, shorter runs (ctest)
    Report& report;
    std::string sandMeshes;                 ///< the sand grains' meshes (the silo)
    std::vector<std::string> siloGrains;    ///< "spheres", "sand": the silo's grain kinds
    std::vector<double> siloOrifices;       ///< D, mm (empty: the plan's)
    double siloRadius = 0.0;                ///< mm (0: the plan's)
    double siloHeight = 0.0;                ///< the fill's height, mm (0: the plan's)
    /// Where a long case says how far it has got (may be empty).
    std::function<void(const std::string&)> progress;

    void note(const std::string& line) const
    {
        if (progress) progress(line);
    }
};

/// Which of the laws asked for a case runs (its cost is shared among them: VerifyCost.h).
enum class CaseLaws {
    Every,       ///< every law asked for
    Frictional,  ///< those with shear springs (per-node forces): friction needs them
    Face,        ///< all but the single-node law, whose one node of a face's hundreds tips a box
    Own,         ///< the case's own law (adapted), whatever is asked
};
/// Whether a case of @a laws runs @a f when it is asked for.
bool caseRunsLaw(CaseLaws laws, Formulation f);
/// The laws of @a c that a case of @a laws runs, in their order.
std::vector<Formulation> lawsOfCase(const Context& c, CaseLaws laws);

/// Chung & Ooi test 2: a ball's elastic normal impact on a wall; overlap, force, duration.
void normalImpactOnWall(Context& c);
/// Chung & Ooi test 1: two equal balls' elastic normal impact.
void normalImpactOfTwoSpheres(Context& c);
/// Chung & Ooi test 3: the rebound of a ball on a wall over restitutions 0.1 … 1.
void restitutionSweep(Context& c);
/// Chung & Ooi test 4: a ball at 3.9 m/s on a wall at 5° … 85° from the normal, μ 0.092.
void obliqueImpactOnWall(Context& c);
/// Chung & Ooi test 5: constant normal speed 5 m/s, tangential speeds swept; μ 0.3, e 1.
void obliqueImpactAtNormalSpeed(Context& c);
/// Chung & Ooi test 7: two equal balls spinning oppositely: no slip.
void spinImpactOfTwoBalls(Context& c);
/// A ball thrown flat on a floor slides, then rolls on at 5/7 of its speed: no resistance, no hops.
void slideToRollOnAFloor(Context& c);
/// A box sliding down an incline of 30° (and resting on one of 10°), μ 0.3.
void boxOnAnIncline(Context& c);
/// A box landing flat: the automatic step bears it, and it rebounds at the restitution given.
void boxLandingFlat(Context& c);
/// A box spinning about its intermediate axis turns over and back (the tennis racket).
void freeRotation(Context& c);
/// The adapted law's errors against its continuum limits shrink as the ball's nodes refine.
void convergence(Context& c);
/// Chung & Ooi test 6: a spinning ball's normal impact on a wall, μ 0.4, e 0.5.
void spinImpactOnWall(Context& c);
/// Chung & Ooi test 8: the same on a ball five times as large and 1000 times as dense.
void spinImpactOnHeavyBall(Context& c);

/// A flat-bottomed silo emptied through orifices of several sizes: Beverloo's law, with
/// spheres and with the sand grains.
void siloDischarge(Context& c);
/// What siloDischarge will take with @a o on 2 cores of this machine: least and most seconds
/// (the packing's time is the least certain part).
std::pair<double, double> siloDischargeSeconds(const VerifyOptions& o);

} // namespace lsdem::verify

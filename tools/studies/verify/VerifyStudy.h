/// @file VerifyStudy.h
/// @brief `lsdem-study verify`: the verification suite (docs/verification.md) as a study:
///        which cases to run, on which laws and bodies, and the report they make.
#pragma once

#include "studies/verify/VerifyReport.h"
#include "studies/verify/VerifySetup.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace lsdem::verify {

struct Context;

struct VerifyOptions
{
    Setup setup;
    std::vector<Formulation> formulations = allFormulations();
    std::vector<std::string> cases;  ///< names of caseList(); empty: all
    bool quick = false;              ///< the fast version (ctest): fewer points, coarser
    std::string sandMeshes = "assets/meshes/sand";  ///< the silo's sand grains
    /// The silo's grain kinds: "spheres", "sand" (the quick version runs spheres only).
    std::vector<std::string> siloGrains = {"spheres", "sand"};
    /// The silo's orifice diameters, mm (empty: the plan's, 5 … 8 mm; 5 and 6 in --quick).
    std::vector<double> siloOrifices;
    /// The silo's radius and fill height, mm (0: 10 and 12; 4 and 8 in --quick); the grain
    /// count follows the fill's volume.
    double siloRadius = 0.0, siloHeight = 0.0;
    std::string outDir = "results/verify";
    bool plots = true, quiet = false;
    bool estimateOnly = false;  ///< print what the run would take, and stop
};

enum class CaseLaws;

/// What a case costs on 2 cores of this machine, for the estimate printed before the suite
/// (VerifyCost.h): measured, not derived (docs/verification.md#cost).
struct CaseCost
{
    double fixed = 0.0;  ///< seconds of the full version whatever the laws (references, bakes)
    /// Seconds of the full version for each law it runs, in allFormulations()' order
    /// (original, adapted, single-node, volume); 0 for a law it does not run. A law added
    /// later costs nothing here until it is measured.
    double perLaw[4] = {0.0, 0.0, 0.0, 0.0};
    double quickShare = 1.0;  ///< the quick version's time over the full one's
    /// Whether it runs the setup's ball (then its cost follows the ball's nodes, and the ball's
    /// bake is counted once, apart).
    bool ball = false;
    /// For a case whose cost follows its own options (the silo): its least and most seconds,
    /// in place of the above.
    std::function<std::pair<double, double>(const VerifyOptions&)> model;
};

/// One case of the suite.
struct CaseEntry
{
    std::string name;
    std::string title;  ///< what it checks, for --help and the summary
    std::function<void(Context&)> run;
    CaseLaws laws;      ///< which of the laws asked for it runs
    CaseCost cost;
    /// Run only when named (--case), or in the quick version: a bulk case that costs hours,
    /// not minutes.
    bool onlyWhenNamed = false;
};

/// Every case, in the order the suite runs them.
const std::vector<CaseEntry>& caseList();
/// Whether @a o runs @a entry.
bool runsCase(const VerifyOptions& o, const CaseEntry& entry);

/// Check @a o; throw Error naming the bad option and the fix.
void checkVerifyOptions(const VerifyOptions& o);

/// Run the cases of @a o (no files written). @a progress, if given, hears a line as each case
/// starts, and the long cases' milestones.
Report runVerification(const VerifyOptions& o,
                       const std::function<void(const std::string&)>& progress = {});

} // namespace lsdem::verify

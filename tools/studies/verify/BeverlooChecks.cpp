// The silo's checks over its orifices (BeverlooChecks.h).
#include "studies/verify/BeverlooChecks.h"

#include <algorithm>
#include <tuple>

namespace lsdem::verify {

void addBeverlooChecks(Context& c, const std::string& name, const std::vector<Discharge>& flows,
                       double rho, double gravity, double grainSize, double siloWidth)
{
    // Beverloo's law holds where the silo's walls do not reach the flow: at least 2.5 orifices
    // and D + 30 d wide (Nedderman 1992; Mankoc et al., Granular Matter 9 (2007) 407). Shown
    // for the largest orifice: the default silo, 20 d wide, is not D + 30 d wide for any D.
    const double largest = flows.back().diameter;
    Check premise{name, "adapted", "silo width over Beverloo's least", "", 1.0,
                  siloWidth / std::max(2.5 * largest, largest + 30.0 * grainSize), 1.0, 0.0,
                  "shown: the width over max(2.5·D, D + 30·d) at the largest D; Beverloo's premise "
                  "wants ≥ 1 (walls clear of the flow); below it the "
                  "walls slow the flow and C and k are not Beverloo's"};
    premise.informative = true;
    c.report.add(premise);
    const BeverlooFit fit = fitBeverloo(flows, rho, gravity, grainSize);
    // Two orifices (the quick version) fix the line exactly: its fit is shown, not judged.
    const bool judged = flows.size() >= 3;
    // Over D = 5–8 d the exponent is weakly determined (a law W ∝ D³ still gives R² 0.9998 for
    // W^(2/5) against D at D = 5, 6, 7, 8): the line's R² and the flows' own exponent are shown, C and k judged.
    Check linear{name, "adapted", "W^(2/5) a line in D: R²", "", 1.0, fit.rSquared, 1.0, 0.0,
                 "shown: over D = 5–8 d even W ∝ D³ gives R² 0.9998"};
    linear.informative = true;
    c.report.add(linear);
    Check cFit{name, "adapted", "Beverloo's C", "", 0.6, fit.c, 0.6, 0.05 / 0.6,
               "C = 0.55–0.65 (Beverloo et al. 1961; Nedderman 1992), with ρ_b measured"};
    cFit.informative = !judged;
    c.report.add(cFit);
    Check kFit{name, "adapted", "Beverloo's k", "", 2.0, fit.k, 1.0, 1.0,
               "k = 1–3 grain sizes (1.4–1.5 for spheres, up to ~3 for angular sand; Nedderman "
               "1992)"};
    kFit.informative = !judged;
    c.report.add(kFit);
    if (judged) {
        // How loosely the orifices fix C and k: their 95 % intervals, shown.
        for (const auto& [quantity, value, reference, scale, tolerance] :
             {std::make_tuple("Beverloo's C, 95 % interval from", fit.cLow95, 0.6, 0.6, 0.05 / 0.6),
              std::make_tuple("Beverloo's C, 95 % interval to", fit.cHigh95, 0.6, 0.6, 0.05 / 0.6),
              std::make_tuple("Beverloo's k, 95 % interval from", fit.kLow95, 2.0, 1.0, 1.0),
              std::make_tuple("Beverloo's k, 95 % interval to", fit.kHigh95, 2.0, 1.0, 1.0)}) {
            Check interval{name, "adapted", quantity, "", reference, value, scale, tolerance,
                           "shown: the slope's interval carried to C, Fieller's for k (Student's t)"};
            interval.informative = true;
            c.report.add(interval);
        }
    }
    Check exponent{name, "adapted", "exponent of W, k as fitted", "", 2.5,
                   fittedExponent(flows, fit.k * grainSize), 2.5, 0.0,
                   "shown: the flows' own exponent, 5/2 in Beverloo's law"};
    exponent.informative = true;
    c.report.add(exponent);
}

} // namespace lsdem::verify

/// @file BeverlooChecks.h
/// @brief The silo's checks over its orifices: Beverloo's C and k fitted to the flows
///        (BeverlooFit.h) and judged against the literature's ranges, with what tells how far
///        to trust them shown beside (their 95 % intervals, the line's R², the flows' own
///        exponent, and the silo's width against Beverloo's premise).
#pragma once

#include "studies/verify/BeverlooFit.h"
#include "studies/verify/VerifyCases.h"

#include <string>
#include <vector>

namespace lsdem::verify {

/// Add to @a c's report the checks of @a flows (at least two, by diameter) of grains of size
/// @a grainSize and bulk density @a rho under gravity @a gravity from a silo @a siloWidth wide
/// (mm); C and k are judged from three orifices on (two fix a line exactly: shown).
void addBeverlooChecks(Context& c, const std::string& name, const std::vector<Discharge>& flows,
                       double rho, double gravity, double grainSize, double siloWidth);

} // namespace lsdem::verify

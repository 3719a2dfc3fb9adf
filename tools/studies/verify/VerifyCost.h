/// @file VerifyCost.h
/// @brief What `lsdem-study verify` will take, printed before its first case: each case's
///        measured time scaled to the laws and the ball asked for, the ball's bake, and for the
///        silo a model of its packing, settling and discharges (the last from Beverloo's law).
#pragma once

#include "studies/verify/VerifyStudy.h"

#include <string>
#include <vector>

namespace lsdem::verify {

struct VerifyEstimate
{
    struct Part
    {
        std::string name;
        double seconds = 0.0;  ///< on 2 cores of this machine
    };
    std::vector<Part> parts;   ///< the ball's bake, then each case to run, in order
    double seconds = 0.0;      ///< their sum
    /// The silo's part, its least and most (its packing's time is the least sure of all).
    double siloLeast = 0.0, siloMost = 0.0;

    /// "about 3.4 min on 2 cores (bake 6 s, normal-wall 9 s, …)".
    std::string text() const;
};

/// The estimate for the cases @a o runs.
VerifyEstimate estimateVerification(const VerifyOptions& o);

} // namespace lsdem::verify

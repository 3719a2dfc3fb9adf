// The tags of the records that ranks exchange about grains (GhostDecomposition.cpp,
// GhostCollectives.cpp). Private to lsdem_simulation.
#pragma once

namespace lsdem::ghostrecords {

/// What a record in an exchange of grains holds.
enum Tag : char {
    kOwnedGrain = 'O',
    kGhostGrain = 'G',
    kPairHistory = 'P',
    kBoundaryHistory = 'B'
};

} // namespace lsdem::ghostrecords

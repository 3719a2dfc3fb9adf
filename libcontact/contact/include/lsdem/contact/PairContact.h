/// @file PairContact.h
/// @brief The whole contact between two grains: narrow phase in one or both directions, then
///        the contact law (ContactLaw.h): forces and torques on both grains (equal and
///        opposite forces; torques about each grain's centroid).
#pragma once

#include "lsdem/contact/ContactLaw.h"

#include <map>
#include <vector>

namespace lsdem {

/// Shear forces carried over between steps, per node, for each direction of testing.
/// std::map keeps iteration (and so any output) in node order.
struct PairHistory
{
    std::map<int, Vec3> shearOnFirstNodes;   ///< nodes of the pair's first grain in the second
    std::map<int, Vec3> shearOnSecondNodes;  ///< nodes of the second grain in the first

    bool empty() const { return shearOnFirstNodes.empty() && shearOnSecondNodes.empty(); }
};

/// Compute the contact of @a first and @a second.
/// @param dt       the step, for the slip increment of the shear springs (0: no shear update)
/// @param history  shear history of this pair, updated in place (may be null when μ = 0)
/// @param forces   if not null, receives every point force (normal + shear) as it acts on
///                 the grain whose node produced it (for output of contact forces)
PairForces computePairContact(const ContactGrain& first, const ContactGrain& second,
                              const ContactModel& model, double dt, PairHistory* history,
                              NodeCheckStats& stats, std::vector<PointForce>* forces = nullptr);

} // namespace lsdem

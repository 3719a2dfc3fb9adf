/// @file PairContact.h
/// @brief The whole contact between two grains: narrow phase in one or both directions, then
///        the contact law (ContactLaw.h): forces and torques on both grains (equal and
///        opposite forces; torques about each grain's centroid).
#pragma once

#include "lsdem/contact/CandidateBlocks.h"
#include "lsdem/contact/ContactLaw.h"

#include <vector>

namespace lsdem {

/// Compute the contact of @a first and @a second.
/// @param dt       the step, for the slip increment of the shear springs (0: no shear update)
/// @param history  shear history of this pair, updated in place (may be null when μ = 0)
/// @param forces   if not null, receives every point force (normal + shear) as it acts on
///                 the grain whose node produced it (for output of contact forces)
/// @param scratch  working memory to reuse (null: a temporary one)
/// @param candidates  the node blocks near the other grain from earlier calls for this pair,
///                 kept up to date (null: found afresh); the result is the same either way
PairForces computePairContact(const ContactGrain& first, const ContactGrain& second,
                              const ContactModel& model, double dt, PairHistory* history,
                              NodeCheckStats& stats, std::vector<PointForce>* forces = nullptr,
                              ContactScratch* scratch = nullptr,
                              PairCandidates* candidates = nullptr);

} // namespace lsdem

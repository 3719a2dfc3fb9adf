/// @file BoundaryContact.h
/// @brief The contact of a grain with a boundary, as computePairContact (PairContact.h) is
///        that of two grains: the grain's nodes inside the boundary (findBoundaryContacts),
///        through the same contact law (resolveContact). Only the grain's side is tested: a
///        boundary has no nodes.
#pragma once

#include "lsdem/contact/CandidateBlocks.h"
#include "lsdem/contact/ContactLaw.h"
#include "lsdem/simulation/Boundary.h"

#include <vector>

namespace lsdem {

/// The contact of @a grain with @a boundary (seen by the law as @a boundaryView).
/// @param dt         the step, for the shear springs' slip (0: no shear update)
/// @param history    the shear history of this grain and boundary, updated in place (may be
///                   null when μ = 0)
/// @param forces     if not null, receives every point force as it acts on the grain
/// @param scratch    working memory to reuse (its contact buffers are handed back)
/// @param candidates for a level-set obstacle, the grain's nodes near it, kept over calls
PairForces computeBoundaryContact(const ContactGrain& grain, const Boundary& boundary,
                                  const ContactGrain& boundaryView, const ContactModel& model,
                                  double dt, ShearHistory* history, NodeCheckStats& stats,
                                  std::vector<PointForce>* forces, ContactScratch& scratch,
                                  CandidateBlocks* candidates);

} // namespace lsdem

#include "lsdem/simulation/BoundaryContact.h"

namespace lsdem {

PairForces computeBoundaryContact(const ContactGrain& grain, const Boundary& boundary,
                                  const ContactGrain& boundaryView, const ContactModel& model,
                                  double dt, ShearHistory* history, NodeCheckStats& stats,
                                  std::vector<PointForce>* forces, ContactScratch& scratch,
                                  CandidateBlocks* candidates)
{
    ContactSide side;
    side.tester = &grain;
    side.other = &boundaryView;
    side.history = history;
    // The scratch's first contact buffer is lent to the side (its capacity reused), then
    // handed back.
    side.contacts.swap(scratch.contacts[0]);
    side.contacts.clear();
    findBoundaryContacts(*grain.asset, grain.pose, boundary, side.contacts, stats, candidates,
                         model.quadrature == NodeQuadrature::Patch);
    const PairForces result = resolveContact(&side, 1, model, dt, forces, &scratch);
    side.contacts.swap(scratch.contacts[0]);
    return result;
}

} // namespace lsdem

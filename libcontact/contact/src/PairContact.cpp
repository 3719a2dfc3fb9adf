#include "lsdem/contact/PairContact.h"

#include <cmath>

namespace lsdem {

PairForces computePairContact(const ContactGrain& first, const ContactGrain& second,
                              const ContactModel& model, double dt, PairHistory* history,
                              NodeCheckStats& stats, std::vector<PointForce>* forces,
                              ContactScratch* scratch, PairCandidates* candidates)
{
    ContactScratch temporary;
    ContactScratch& work = scratch ? *scratch : temporary;
    bool testFirst = true, testSecond = true;
    double weight = 0.5;
    if (model.testing == NodeTesting::OneWay) {
        // The smaller grain's nodes; on a tie (within round-off), the lower index's.
        const double ra = first.asset->boundingRadius, rb = second.asset->boundingRadius;
        const bool tie = std::abs(ra - rb) <= 1e-9 * std::max(ra, rb);
        testFirst = tie ? first.index <= second.index : ra < rb;
        testSecond = !testFirst;
        weight = 1.0;
    }
    const bool patches = model.quadrature == NodeQuadrature::Patch;
    // A direction not tested carries no history.
    if (history && !testFirst) history->shearOnFirstNodes.clear();
    if (history && !testSecond) history->shearOnSecondNodes.clear();

    ContactSide sides[2];
    int count = 0;
    if (testFirst) {
        ContactSide& s = sides[count++];
        s.tester = &first;
        s.other = &second;
        s.weight = weight;
        s.history = history ? &history->shearOnFirstNodes : nullptr;
        s.contacts.swap(work.contacts[count - 1]);  // reuse the thread's buffer
        s.contacts.clear();
        findNodeContacts(*first.asset, first.pose, *second.asset, second.pose, s.contacts, stats,
                         candidates ? &candidates->ofFirst : nullptr, patches);
    }
    if (testSecond) {
        ContactSide& s = sides[count++];
        s.tester = &second;
        s.other = &first;
        s.weight = weight;
        s.history = history ? &history->shearOnSecondNodes : nullptr;
        s.contacts.swap(work.contacts[count - 1]);
        s.contacts.clear();
        findNodeContacts(*second.asset, second.pose, *first.asset, first.pose, s.contacts,
                         stats, candidates ? &candidates->ofSecond : nullptr, patches);
    }
    PairForces result = resolveContact(sides, count, model, dt, forces, &work);
    for (int k = 0; k < count; ++k) sides[k].contacts.swap(work.contacts[k]);  // hand back
    if (!testFirst) {
        // resolveContact names the first side's tester "first": swap back to the caller's.
        std::swap(result.forceOnFirst, result.forceOnSecond);
        std::swap(result.torqueOnFirst, result.torqueOnSecond);
        std::swap(result.rotationalStiffnessOfFirst, result.rotationalStiffnessOfSecond);
        std::swap(result.dashpotArmOfFirst, result.dashpotArmOfSecond);
        result.normal = -result.normal;  // it pushed the tester out: now the caller's first
        result.pointForcesOnFirst = 0;
    }
    return result;
}

} // namespace lsdem

#include "lsdem/simulation/ContactBackend.h"

#include "lsdem/contact/PairContact.h"
#include "lsdem/core/ThreadPrivate.h"
#include "lsdem/simulation/BoundaryContact.h"
#include "SlotPrefetch.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace lsdem {

void computeContactSlot(const ContactBatch& batch, size_t k, ContactScratch& scratch)
{
    const World& w = batch.world;
    ContactSlot& s = batch.slots[k];
    s.stats = NodeCheckStats();
    s.forces.clear();
    std::vector<PointForce>* out = batch.recordForces ? &s.forces : nullptr;
    const int material = w.grains[s.first].material;
    if (s.boundary < 0) {
        const ContactModel& m = w.model(material, w.grains[s.second].material);
        // Across a periodic cell's face, the second grain's image.
        ContactGrain image;
        const bool shifted = !s.periods.isZero(0.0);
        if (shifted) {
            const Vec3 shift = w.periodic.imageShift(s.periods);
            image = batch.grains[s.second];
            image.pose.position += shift;
            // (A deforming cell carries its images along: they move with its faces.)
            image.velocity += w.periodic.strainRate.cwiseProduct(shift);
        }
        s.result = computePairContact(batch.grains[s.first], shifted ? image : batch.grains[s.second],
                                      m, batch.slipStep, s.pairHistory, s.stats, out, &scratch,
                                      &s.candidates);
    } else {
        const Boundary& b = w.boundaries[s.boundary];
        // A level-set obstacle remembers the grain's nodes near it, as a grain pair does.
        s.result = computeBoundaryContact(batch.grains[s.first], b, batch.boundaries[s.boundary],
                                          w.model(material, b.material), batch.slipStep,
                                          s.boundaryHistory, s.stats, out, scratch,
                                          &s.candidates.ofFirst);
    }
    batch.totals[k] = {s.stats, s.result.elasticEnergy, s.result.contactNodes};
}

namespace {

/// Slots [@a begin, @a end) of @a batch in order, each one's scattered state asked for ahead
/// of its turn: its histories two slots before, the arrays they point to one slot before.
void computeSlotsFetchingAhead(const ContactBatch& batch, size_t begin, size_t end,
                               ContactScratch& scratch)
{
    const std::vector<ContactSlot>& slots = batch.slots;
    for (size_t k = begin; k < std::min(end, begin + 2); ++k) prefetchHistories(slots[k]);
    if (begin < end) prefetchArrays(slots[begin]);
    for (size_t k = begin; k < end; ++k) {
        if (k + 2 < end) prefetchHistories(slots[k + 2]);
        if (k + 1 < end) prefetchArrays(slots[k + 1]);
        computeContactSlot(batch, k, scratch);
    }
}

class CpuContactBackend final : public ContactBackend
{
public:
    std::unique_ptr<ContactBackend> clone() const override
    {
        return std::make_unique<CpuContactBackend>();
    }

    void compute(const ContactBatch& batch) override
    {
        // Ranges of slots; nothing shared is written.
        tbb::parallel_for(tbb::blocked_range<size_t>(0, batch.slots.size()),
                          [&](const tbb::blocked_range<size_t>& range) {
                              computeSlotsFetchingAhead(batch, range.begin(), range.end(),
                                                        mScratch.local().value);
                          });
    }

private:
    /// Each thread's working memory for the contact laws (no allocation in the hot loop).
    tbb::enumerable_thread_specific<ThreadPrivate<ContactScratch>> mScratch;
};

} // namespace

std::unique_ptr<ContactBackend> makeCpuContactBackend()
{
    return std::make_unique<CpuContactBackend>();
}

} // namespace lsdem

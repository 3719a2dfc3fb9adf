/// @file ContactBackend.h
/// @brief The seam between a Simulation and whatever computes its contacts: each step the
///        simulation hands a backend the batch of contact slots (the narrow phase and the laws
///        of every candidate pair and grain–boundary contact) and sums what comes back in a
///        fixed order. The CPU backend runs the slots on TBB's threads; another backend (a
///        device, docs/gpu.md) implements compute() and nothing of the physics changes. A
///        slot's numbers depend on its own inputs only, so every backend that computes each
///        slot with computeContactSlot gives the same bits, in any order.
#pragma once

#include "lsdem/simulation/ContactList.h"
#include "lsdem/simulation/World.h"

#include <memory>
#include <vector>

namespace lsdem {

/// Of each slot, what the pass after the narrow phase sums, filled beside it: read in order
/// from one array it streams; read from the slots (688 bytes apart, each last written by
/// whichever thread computed it) it cost a cache miss or a transfer from the other core per
/// slot.
struct ContactSlotTotals
{
    NodeCheckStats stats;
    double elasticEnergy = 0.0;
    long long contactNodes = 0;
};

/// One step's contacts to compute.
struct ContactBatch
{
    const World& world;
    const std::vector<ContactGrain>& grains;      ///< the bodies as the laws see them, by index
    const std::vector<ContactGrain>& boundaries;  ///< likewise, by boundary index
    std::vector<ContactSlot>& slots;              ///< to fill: result, stats, point forces
    std::vector<ContactSlotTotals>& totals;       ///< one per slot, to fill beside it
    double slipStep;    ///< the step over which shear slips (0: none)
    bool recordForces;  ///< keep each slot's point forces
};

/// Computes slot @a k of @a batch (its narrow phase and law, into the slot and its totals) with
/// @a scratch as working memory. Touches nothing of the other slots.
void computeContactSlot(const ContactBatch& batch, size_t k, ContactScratch& scratch);

class ContactBackend
{
public:
    virtual ~ContactBackend() = default;
    /// A fresh backend of the same kind (a copied Simulation gets its own).
    virtual std::unique_ptr<ContactBackend> clone() const = 0;
    /// Fill every slot of @a batch and its totals.
    virtual void compute(const ContactBatch& batch) = 0;
};

/// The CPU backend: the slots in parallel on TBB's threads, each thread with its own reused
/// working memory.
std::unique_ptr<ContactBackend> makeCpuContactBackend();

/// A backend owned by value: copies clone it (so a Simulation stays copyable).
class ContactBackendHolder
{
public:
    ContactBackendHolder() : mBackend(makeCpuContactBackend()) {}
    ContactBackendHolder(const ContactBackendHolder& other) : mBackend(other.mBackend->clone()) {}
    ContactBackendHolder& operator=(const ContactBackendHolder& other)
    {
        if (this != &other) mBackend = other.mBackend->clone();
        return *this;
    }
    ContactBackendHolder(ContactBackendHolder&&) noexcept = default;
    ContactBackendHolder& operator=(ContactBackendHolder&&) noexcept = default;

    void reset(std::unique_ptr<ContactBackend> backend) { mBackend = std::move(backend); }
    ContactBackend& operator*() const { return *mBackend; }

private:
    std::unique_ptr<ContactBackend> mBackend;
};

} // namespace lsdem

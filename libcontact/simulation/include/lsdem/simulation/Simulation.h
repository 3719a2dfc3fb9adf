/// @file Simulation.h
/// @brief Explicit time stepping of a World: velocity Verlet (RigidBody.h) around a force
///        evaluation made of a broad phase (BroadPhase.h), the node contacts of every candidate
///        pair and every grain near a boundary, computed in parallel (TBB) into one slot per
///        contact and summed in a fixed order, so results are identical for any thread count.
#pragma once

#include "lsdem/simulation/ContactBackend.h"
#include "lsdem/simulation/ContactList.h"
#include "lsdem/simulation/MembraneContact.h"
#include "lsdem/simulation/StableStep.h"
#include "lsdem/simulation/World.h"

#include <string>
#include <vector>

namespace lsdem {

class GhostDecomposition;

/// Energies now (force·length). Dissipated energy is what the balance leaves over:
/// boundary work − (kinetic + elastic + potential − their initial total). The mechanisms'
/// sums (the grains' DissipatedEnergy) split it; what they leave of it is the integrator's
/// error, O(dt) over a run.
struct Energies
{
    double kinetic = 0.0, elastic = 0.0, potential = 0.0, boundaryWork = 0.0, dissipated = 0.0;
    double friction = 0.0, dashpot = 0.0, globalDamping = 0.0;
};

/// Where the time of the force evaluations went, and how much was done.
struct StepCounters
{
    double broadSeconds = 0.0, narrowSeconds = 0.0, integrateSeconds = 0.0;
    long long steps = 0;
    long long candidatePairs = 0;    ///< summed over steps (grain pairs on the contact list)
    long long listRebuilds = 0;      ///< times the contact list was rebuilt
    long long boundaryCandidates = 0;
    NodeCheckStats nodes;             ///< summed over steps
};

/// One contact force for output: the point force as it acts on grain @a grain
/// (a boundary's reaction is not listed; its total is Boundary::force).
struct ContactForceRecord
{
    Vec3 point = Vec3::Zero();
    Vec3 force = Vec3::Zero();
    int grain = 0;
};

/// One contact of the last evaluation as a whole (micromechanics, Python): its two bodies, the
/// resultant force on the first, where it acts and along which normal, and its nodes.
struct ContactRecord
{
    int first = 0;       ///< grain index
    int second = -1;     ///< the other grain's index, or -1 ...
    int boundary = -1;   ///< ... the boundary's index, or -1 ...
    int membrane = -1;   ///< ... the membrane's index
    Vec3 force = Vec3::Zero();   ///< resultant on first (second gets the opposite)
    Vec3 centre = Vec3::Zero();  ///< stiffness-weighted centre of its point forces
    Vec3 normal = Vec3::Zero();  ///< unit, pushing first out of the other body
    int nodes = 0;               ///< penetrating nodes, both sides
    /// Σ (x_n − centre) ⊗ f_n over its point forces on first: the part of its moment that the
    /// resultant at the centre misses. Kept for a membrane's contacts, whose nodes fan round a
    /// grain the membrane wraps (a quarter of the grains' stress moment, measured on 27 grains
    /// in a membrane); zero for the others, whose patches are small beside a grain.
    Mat3 spread = Mat3::Zero();
    /// In a periodic cell, the periods added to second's position: it touches first as that
    /// image (where centre and the branch vector are measured).
    Vec3 shift = Vec3::Zero();
};

class Simulation
{
public:
    /// Take over @a world and step it by @a dt. If @a evaluateInitialForces, the forces at
    /// the current state are computed (a fresh start); a restart passes false because the
    /// grains' forces come from the checkpoint. @a recordContactForces: as
    /// setRecordContactForces, from the initial evaluation on (so a first frame has them).
    Simulation(World world, double dt, bool evaluateInitialForces = true,
               bool recordContactForces = false);
    /// Split by space over the ranks of @a ghosts (GhostDecomposition.h): @a world is the
    /// whole simulation, the same on every rank; this rank keeps its owned grains and their
    /// ghosts, and world() is that part (grains in global order; globalIds() maps them).
    /// Every rank constructs and steps its simulation in step with the others; energies() and
    /// contactNodes() are then collective. @a ghosts must outlive the simulation.
    Simulation(World world, double dt, bool evaluateInitialForces, bool recordContactForces,
               GhostDecomposition& ghosts);

    /// Advance one step: half kick, drift, forces, half kick.
    /// @throw Error if the state becomes non-finite or a contact is stiffer than dt allows.
    void step();

    double timeStep() const { return mDt; }
    const World& world() const { return mWorld; }
    /// The world, to change between steps. Moved grains and boundaries are noticed by the
    /// contact list; after changing anything else that it holds (grains added or removed,
    /// assets, the shear histories), call invalidateContacts().
    World& world() { return mWorld; }
    /// Rebuild the contact list at the next step.
    void invalidateContacts() { mContacts.markStale(); }
    /// Collective when split by space (every rank calls it, the same result on each).
    Energies energies() const;
    const StepCounters& counters() const { return mCounters; }

    /// Keep the point forces of the last evaluation (for VTK frames); off by default. Split by
    /// space, those on this rank's owned grains, by global grain index.
    void setRecordContactForces(bool on) { mRecordForces = on; }
    const std::vector<ContactForceRecord>& contactForces() const { return mForces; }
    /// Penetrating nodes at the last evaluation (collective when split by space).
    long long contactNodes() const;
    /// Elastic energy at the last evaluation.
    double elasticEnergy() const { return mElastic; }
    /// How many other grains each grain touched (a penetrating node either way) at the last
    /// evaluation, by grain index: the coordination of granular mechanics (walls not counted).
    /// Split by space: over this rank's contacts, by the index of its world (not collective).
    std::vector<int> grainContactCounts() const;
    /// Every contact with a penetrating node at the last evaluation, grain pairs first, in the
    /// contact list's order (the same on any thread count). Split by space: this rank's, by the
    /// index of its world (not collective).
    std::vector<ContactRecord> contactRecords() const;
    /// Collective when split by space: every contact of the whole simulation as one process
    /// lists it (contactRecords(): grains by their global index, in its list order), on every
    /// rank. Otherwise contactRecords().
    std::vector<ContactRecord> wholeContactRecords() const;
    /// Collective when split by space: the whole world as one process holds it, on rank 0 (the
    /// others get an empty one; GhostDecomposition::gatherWorld). Otherwise a copy.
    World wholeWorld() const;
    /// Collective when split by space: rank 0's @a numbers on every rank (the others' are not
    /// read). Otherwise @a numbers.
    std::vector<double> numbersFromRankZero(const std::vector<double>& numbers) const;
    /// The largest stable step seen so far for the stiffest grain contact (infinite if none).
    double stabilityLimitSeen() const { return mStabilityLimit; }
    /// Compute the contacts with @a backend from the next step on (ContactBackend.h; the CPU's
    /// by default). Every backend that computes each slot with computeContactSlot gives the
    /// same numbers.
    void setContactBackend(std::unique_ptr<ContactBackend> backend)
    {
        mBackend.reset(std::move(backend));
    }
    /// The split by space given at construction (null: none).
    const GhostDecomposition* ghosts() const { return mGhosts; }

private:
    /// Forces, torques and the contacts' stiffnesses on every grain, in phases:
    void evaluateForces(double slipStep);
    /// Split by space: ghosts follow their owners; grains change rank when the list is rebuilt.
    void followGhosts();
    /// The contact list (rebuilt when something moved more than half the skin) and each body
    /// as the contact laws see it.
    void updateContactList();
    /// The narrow phase and the contact law of every slot, in parallel.
    void computeContacts(double slipStep);
    /// Each grain's force, torque and stiffness from its slots in list order, plus gravity and
    /// global damping; what they dissipated over @a dt added to its DissipatedEnergy.
    void sumGrainForces(double dt);
    /// A deforming periodic cell's measures at this evaluation: the moment its strain rates
    /// put power in through (EnergyBook::cellMoment) and the stress on it (PeriodicCell::stress).
    void measureCell();
    /// Node-check statistics, nodes in contact and elastic energy over the slots.
    void sumContactCounts();
    /// The boundaries' reactions and, when recorded, the point forces, in slot order.
    void collectReactionsAndPointForces();
    /// Throws if a grain's state is no longer finite or the step exceeds its stable limit;
    /// @a atStart, also the limit of the stiffest contact a grain near another body can make.
    void checkStability(bool atStart = false);
    /// Grain @a i's stable step limit: infinite for a grain that is not free, integrated here
    /// and in contact; NaN if its state is no longer finite.
    double stepLimitOf(size_t i) const;
    /// The verdict on @a limits (one per grain), in grain order, so the message is the same on
    /// any thread count. @a forecast: they are the stiffest contacts' (not recorded as seen).
    void judgeStepLimits(const std::vector<double>& limits, bool forecast);
    /// Split by space: this rank's part of the boundaries' reactions, summed over the ranks
    /// in the one-process order.
    void sumBoundaryReactions();
    /// The power the prescribed grains take (F·v + τ·ω) subtracted from @a work in grain
    /// order (split by space: gathered from their owners, in the same order).
    void subtractPrescribedPower(double& work);
    /// Split by space: the first grain (global order) whose state or stability fails on any
    /// rank throws, on every rank.
    void checkStabilityOverRanks(const std::vector<double>& limits, bool forecast);
    /// Split by space: the time spent so far exchanging with the other ranks (kept out of the
    /// broad phase and integration times).
    double exchangedSeconds() const;
    /// Whether grain @a i of this world is integrated here (not a ghost).
    bool integratesGrain(size_t i) const;

    // The membranes (SimulationMembranes.cpp).
    /// @throw Error if a membrane is unfinished or names a material or boundary not there.
    void checkMembranes() const;
    /// Their vertices' first half kick and drift (held ones follow their boundaries).
    void moveMembranes(double dt);
    void kickMembranes(double halfStep);
    /// Their forces: rubber, pressure and the grains' contacts (each grain's kept for
    /// sumGrainForces), with global damping on their free vertices.
    void computeMembranes(double dt);
    /// Membrane @a k's share of its grains' contacts: their reactions on its vertices (forces,
    /// grainForces), the stiffness they add and their elastic energy, in grain order (split by
    /// space, gathered from the grains' owners so that every rank holds the same membrane).
    void addGrainReactions(size_t k);
    /// The power that the pressure puts in (at the vertices' velocities now and the forces of
    /// the last evaluation). The holders' is the boundaries' (addMembraneRimForces).
    double membraneExternalPower() const;
    /// A held vertex pulls on the boundary that holds it (a membrane sealed to a platen): its
    /// force added to the boundary's (Boundary::force), where the boundaries' work and servos
    /// see it.
    void addMembraneRimForces();
    /// Their stable step (rubber and the grains' contacts on free vertices); @a which gets
    /// the membrane that sets it, and its parts.
    double membraneStepLimit(std::string* which = nullptr) const;
    /// Membrane @a k's bounds: ω² of its rubber, the largest ω² of a free vertex on the
    /// grains' contacts (stiffness over mass) and the largest rate of their dashpots on one
    /// (damping over mass), each vertex's share of its pairs included (MembraneGrainContact).
    struct MembraneStepParts
    {
        double rubber = 0.0, contacts = 0.0, contactDamping = 0.0;
    };
    MembraneStepParts membraneStepParts(size_t k) const;
    /// @throw Error if the step exceeds membraneStepLimit().
    void judgeMembraneStep() const;
    /// At the start: a membrane that grains already press may be pressed as hard as the
    /// stiffest contact a grain can make on a vertex (stiffestMembraneContact) within the next
    /// steps. As for grains (checkStability), only a step beyond twice that contact's limit is
    /// refused. @throw Error naming the membrane.
    void judgeMembraneForecast() const;
    /// Their elastic energy (rubber and contacts with grains); @a kinetic gets their vertices'.
    double membraneEnergy(double& kinetic) const;

    World mWorld;
    double mDt = 0.0;
    bool mRecordForces = false;
    std::vector<ContactForceRecord> mForces;
    long long mContactNodes = 0;
    double mElastic = 0.0;
    double mStabilityLimit = 0.0;
    double mLargestDampingRatio = 0.0;  ///< of the world's contact models: the step's margin
    std::vector<GrainStiffness> mGrainStiffness;  ///< per grain at the last evaluation
    ContactList mContacts;
    std::vector<ContactGrain> mViews, mBoundaryViews;  ///< the bodies as the contact laws see them
    using SlotTotals = ContactSlotTotals;
    std::vector<SlotTotals> mSlotTotals;  ///< per slot, filled by the backend beside it
    std::vector<SlotTotals> mRunTotals;  ///< mSlotTotals summed by runs of slots
    std::vector<double> mStepLimits;  ///< per grain, at the last stability check
    StepCounters mCounters;
    GhostDecomposition* mGhosts = nullptr;
    bool mHasPrescribed = false;  ///< some grain of the whole simulation is prescribed
    bool mFreshlyDistributed = false;  ///< split by space, not yet evaluated
    ContactBackendHolder mBackend;  ///< computes the contact slots (the CPU's by default)

    // Per membrane: its triangles binned, each grain's contact with it and what the grains'
    // contacts put on each vertex for its step (MembraneVertexLoad, summed).
    std::vector<MembraneTriangleGrid> mMembraneGrids;
    std::vector<std::vector<MembraneGrainContact>> mMembraneContacts;
    std::vector<std::vector<double>> mMembraneContactStiffness, mMembraneContactDamping;
    double mMembraneElastic = 0.0;  ///< of the grains' contacts with membranes
    long long mMembraneNodes = 0;   ///< grains' nodes in contact with membranes
    NodeCheckStats mMembraneStats;
};

} // namespace lsdem

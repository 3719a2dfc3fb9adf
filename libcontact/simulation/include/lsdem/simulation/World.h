/// @file World.h
/// @brief The state of a running simulation: loaded assets, grains (rigid bodies made from
///        shared assets), boundaries, the contact model of every pair of materials, the shear
///        history of every contact, time and the energy bookkeeping. buildWorld
///        (lsdem/scene/BuildWorld.h) makes one from a scene.
#pragma once

#include "lsdem/simulation/Boundary.h"
#include "lsdem/contact/PairContact.h"
#include "lsdem/simulation/RigidBody.h"
#include "lsdem/simulation/GrainMotion.h"
#include "lsdem/simulation/Membrane.h"
#include "lsdem/simulation/PeriodicCell.h"

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lsdem {

/// Energy dissipated so far (force·length) by the contacts whose first body a grain is (each
/// contact counts once, with its first grain: the owner of its sum on any rank) and by the
/// global damping of its own motion. Summed over grains, it splits Energies::dissipated by
/// mechanism; each grain's share also shows where the energy went.
struct DissipatedEnergy
{
    double friction = 0.0;       ///< taken by the Coulomb caps of the shear springs
    double dashpot = 0.0;        ///< by the contacts' dashpots
    double globalDamping = 0.0;  ///< by World::globalDamping (numerical, not physical)
};

struct Grain
{
    std::string name;
    std::shared_ptr<const GrainAsset> asset;
    int material = 0;
    GrainMotion motion = GrainMotion::Free;
    RigidBody body;                       ///< pose, velocity, angular momentum, mass, inertia
    Vec3 prescribedAngularVelocity = Vec3::Zero();  ///< Prescribed: ω (body.velocity is v)
    Vec3 force = Vec3::Zero();            ///< on it at the last force evaluation (damped)
    Vec3 torque = Vec3::Zero();           ///< about its centroid, likewise
    DissipatedEnergy dissipated;
    /// In a periodic cell: the whole periods the grain was moved by to stay in the cell, so
    /// unwrappedPosition() is where its motion took it (displacements, potential energy).
    Vec3 wrapShift = Vec3::Zero();

    bool isFree() const { return motion == GrainMotion::Free; }
    Vec3 unwrappedPosition() const { return body.pose.position - wrapShift; }
    Vec3 angularVelocity() const
    {
        return motion == GrainMotion::Prescribed ? prescribedAngularVelocity
               : motion == GrainMotion::Fixed    ? Vec3::Zero()
                                                 : body.angularVelocity();
    }
};

/// Running totals for the energy balance (all in force·length).
struct EnergyBook
{
    /// Work done on the grains by moving boundaries, prescribed grains and a deforming periodic
    /// cell.
    double boundaryWork = 0.0;
    double initialTotal = 0.0;  ///< kinetic + elastic + potential at time 0
    /// What a deforming periodic cell's strain rates multiply into the power it puts into the
    /// grains through their contacts, at the last evaluation: per axis, Σ over pairs of the
    /// branch vector times the force on the first grain, less Σ over grains on boundaries of
    /// their place (from the cell's origin) times the force on them (power = ε̇ · this).
    Vec3 cellMoment = Vec3::Zero();
};

struct World
{
    std::vector<std::shared_ptr<const GrainAsset>> assets;  ///< per Scene::assets entry
    std::vector<Grain> grains;
    std::vector<Boundary> boundaries;
    std::vector<Membrane> membranes;  ///< flexible shells (Membrane.h); not yet split by space
    int materialCount = 0;
    std::vector<ContactModel> models;          ///< materialCount², symmetric
    std::vector<std::string> materialNames;
    Vec3 gravity = Vec3::Zero();
    double globalDamping = 0.0;
    PeriodicCell periodic;  ///< inactive unless the scene gives one

    double time = 0.0;
    long long step = 0;
    /// Shear history per grain pair (i < j) and per (grain, boundary). A running Simulation's
    /// contact list points into these maps: change them only before it is made (as a restart
    /// does) or call Simulation::invalidateContacts() afterwards. Empty histories are
    /// bookkeeping of that list, not state.
    std::map<std::pair<int, int>, PairHistory> pairHistory;
    std::map<std::pair<int, int>, ShearHistory> boundaryHistory;
    EnergyBook energy;

    const ContactModel& model(int materialA, int materialB) const
    {
        return models[static_cast<size_t>(materialA) * materialCount + materialB];
    }
};

} // namespace lsdem

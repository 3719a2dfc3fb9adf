/// @file Boundary.h
/// @brief Rigid boundaries of a simulation: planes (walls, optionally finite patches), a sphere
///        (an indenter), level-set obstacles (an asset used as a rigid body), the side wall
///        of a cylinder (a container: grains inside) and a plate with a circular hole (a
///        silo's floor and its orifice). Each moves at a
///        prescribed velocity (zero: fixed) or, for a servo plane, at the velocity that keeps
///        a target stress (StressServo.h); grains touch it with their nodes, through the same
///        contact laws as grain–grain contacts.
#pragma once

#include "lsdem/contact/NodeContact.h"
#include "lsdem/contact/PlaneContact.h"
#include "lsdem/simulation/BoundaryShape.h"
#include "lsdem/simulation/StressServo.h"

#include <memory>
#include <string>
#include <vector>

namespace lsdem {

struct Boundary
{
    std::string name;
    BoundaryShape shape = BoundaryShape::Plane;
    int material = 0;
    Plane plane;                                  ///< Plane: where it started
    Vec3 center = Vec3::Zero();                   ///< Sphere: where its centre started;
                                                  ///< Cylinder: a point of its axis;
                                                  ///< Orifice: the hole's centre, mid-plate
    double radius = 0.0;                          ///< Sphere, Cylinder; Orifice: the hole's
    Vec3 axis = Vec3::UnitZ();                    ///< Cylinder, Orifice: unit axis
    double thickness = 0.0;                       ///< Orifice: the plate's, > 0
    std::shared_ptr<const GrainAsset> asset;      ///< LevelSet
    RigidPose pose;                               ///< LevelSet: where it started
    Vec3 velocity = Vec3::Zero();                 ///< prescribed, world
    Vec3 displacement = Vec3::Zero();             ///< moved so far
    /// Reaction: the grains' force on it (and a membrane's whose rim it holds).
    Vec3 force = Vec3::Zero();
    /// Σ k n·n of its contacts at the last force evaluation (force/length, along its normal;
    /// planes only, 0 for the others): what a servo wall's gain is based on.
    double normalStiffness = 0.0;
    /// Σ c of the viscous dashpots of its contacts, likewise (force·time/length).
    double normalDashpot = 0.0;
    StressServo servo;                            ///< Plane: keeps a target stress if active

    /// Its reference point now (plane point, sphere centre, obstacle centroid, the point of
    /// a cylinder's axis or an orifice's centre).
    Vec3 referencePoint() const;
    /// Whether a grain whose surface lies within @a radius of @a center may touch it.
    bool mayTouch(const Vec3& center, double radius) const;
};

/// Append every node of grain @a a (at @a pose) inside boundary @a b, in node order, with the
/// boundary's outward normal (pushing the grain out) and the contact point halfway to its
/// surface.
/// @param candidates  for a level-set obstacle, the grain's nodes near it remembered from
///                    earlier calls for this grain and boundary (CandidateBlocks.h), kept up
///                    to date; the other shapes ignore it. The contacts are the same either way.
/// With @a patches, each node's contact is integrated over its patch (PatchQuadrature.h; the
/// asset must carry its node shapes): for the shapes integratesPatches() names.
void findBoundaryContacts(const GrainAsset& a, const RigidPose& pose, const Boundary& b,
                          std::vector<NodeContact>& out, NodeCheckStats& stats,
                          CandidateBlocks* candidates = nullptr, bool patches = false);

/// Whether contacts with a boundary of shape @a shape can be integrated over node patches
/// (planes, spheres and level sets; not yet cylinders and orifices).
bool integratesPatches(BoundaryShape shape);

} // namespace lsdem

/// @file ReferenceForces.h
/// @brief The reference-force regression data (tests/data/reference_forces/<formulation>.txt):
///        two bodies in six kinds of contact, their states at two evaluations and the forces,
///        torques, node count and elastic energy expected; how the test recomputes them; the
///        small analytic assets it bakes; and, for regeneration, the cases themselves.
#pragma once

#include "lsdem/contact/PairContact.h"
#include "lsdem/simulation/Boundary.h"

#include <string>
#include <vector>

namespace lsdem::test::reference {

/// grain-grain-one-way, grain-grain-symmetric, grain-plane, grain-patch, grain-sphere,
/// grain-level-set.
const std::vector<std::string>& kindNames();

struct BodyState
{
    RigidPose pose;
    Vec3 velocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
};

/// One force evaluation: the state of the bodies and the step over which they slipped.
struct Evaluation
{
    double dt = 0.0;
    BodyState first;   ///< the first grain
    BodyState second;  ///< the second grain (grain–grain kinds)
    Vec3 boundaryVelocity = Vec3::Zero();      ///< boundary kinds
    Vec3 boundaryDisplacement = Vec3::Zero();  ///< boundary kinds
};

/// What an evaluation gives: on the first grain and on the second body (grain or boundary;
/// a boundary's torque is about its reference point).
struct Outcome
{
    int nodes = 0;
    Vec3 forceFirst = Vec3::Zero(), torqueFirst = Vec3::Zero();
    Vec3 forceSecond = Vec3::Zero(), torqueSecond = Vec3::Zero();
    double elasticEnergy = 0.0;
};

struct Case
{
    std::string kind;
    ContactModel model;
    std::string firstAsset;
    double firstMass = 0.0;
    std::string secondAsset;  ///< the second grain's, or the level-set obstacle's
    double secondMass = 0.0;  ///< grain–grain kinds
    Boundary boundary;        ///< boundary kinds: shape and start (moves per evaluation)
    std::vector<Evaluation> evaluations;
    std::vector<Outcome> expected;
};

bool isGrainPair(const Case& c);

/// The assets the cases name, baked once with fixed options ("sphere", "box").
const GrainAsset& referenceAsset(const std::string& name);
/// How each asset is made, for the files' headers.
std::vector<std::string> assetRecipes();

/// Run the evaluations of @a c in order, carrying the shear history from one to the next, as
/// Simulation::evaluateForces does (computePairContact for grains; findBoundaryContacts and
/// resolveContact for boundaries).
std::vector<Outcome> evaluate(const Case& c);

/// The smallest distance of any node of either body from the surface it is tested against
/// (or from a patch's edges): nodes this close could flip in or out of contact on round-off.
double contactMargin(const Case& c, const Evaluation& e);

/// tests/data/reference_forces/<formulation>.txt in the source tree.
std::string referenceFilePath(Formulation f);

/// Read a reference file. @throw std::runtime_error naming the line for malformed input.
std::vector<Case> readReferenceFile(const std::string& path, Formulation& formulation);

/// Write @a cases (with their expected outcomes) and a header holding @a checks.
/// `git status` of the source tree's tracked files: empty when every change is committed (a
/// reference file is generated only from such a tree, so its header's commit reproduces it).
std::string uncommittedChanges();

void writeReferenceFile(const std::string& path, Formulation f, const std::vector<Case>& cases,
                        const std::vector<std::string>& checks);

/// The cases of formulation @a f, with poses chosen by hand (expected outcomes not filled).
std::vector<Case> generateCases(Formulation f);

/// Compare the cases' first evaluations, recomputed at rest without shear or damping, with
/// closed forms and with each other; lines for the file header. Failures are test failures.
std::vector<std::string> plausibilityChecks(Formulation f, const std::vector<Case>& cases);

} // namespace lsdem::test::reference

/// @file ContactModel.h
/// @brief The parameters of a contact between two grains: formulation, stiffnesses, friction
///        and which nodes are tested. Units are the user's (e.g. mm, N, s).
#pragma once

#include <string>

namespace lsdem {

/// How the penetrating nodes of a contact become a force (SCIENCE.md §2).
enum class Formulation {
    Original,    ///< F_a = kn·d_a·n_a per node; kn in force/length
    Adapted,     ///< F_a = kn*·d_a·A_a·n_a per node; kn* in force/length³ (traction/length)
    SingleNode,  ///< one force kn·d_max·n from the deepest node; kn in force/length
    Volume,      ///< F = kv·V·n̄ with V = Σ d_a·A_a; kv in force/length³
};

/// Which grain's nodes are tested against the other's level set.
enum class NodeTesting {
    OneWay,     ///< the smaller grain's nodes (by bounding radius; ties: the lower index)
    Symmetric,  ///< both grains' nodes, each direction at half weight
};

struct ContactModel
{
    Formulation formulation = Formulation::Adapted;
    NodeTesting testing = NodeTesting::Symmetric;
    double normalStiffness = 0.0;  ///< kn or kn* (see Formulation for units)
    double shearStiffness = 0.0;   ///< ks (force/length) or ks* (force/length³), per node
    double friction = 0.0;         ///< Coulomb coefficient μ
    /// Viscous normal damping as a fraction β of critical damping (0: none). A contact of
    /// total normal stiffness K between effective mass m gets the dashpot 2β·sqrt(m·K),
    /// shared between its point forces in proportion to their stiffness.
    double dampingRatio = 0.0;
};

/// β for a linear spring-dashpot whose rebound speed is @a restitution times the impact speed:
/// β = -ln e / sqrt(π² + ln² e). @a restitution in (0, 1]; 1 gives 0.
double dampingRatioFromRestitution(double restitution);

/// "original", "adapted", "single-node", "volume".
std::string formulationName(Formulation f);
/// Inverse of formulationName. @throw Error naming the accepted values.
Formulation parseFormulation(const std::string& name);

std::string nodeTestingName(NodeTesting t);
NodeTesting parseNodeTesting(const std::string& name);

/// The unit of the normal stiffness for @a f, in words ("force/length", ...).
std::string stiffnessUnit(Formulation f);

} // namespace lsdem

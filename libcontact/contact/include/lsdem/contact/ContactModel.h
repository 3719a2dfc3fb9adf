/// @file ContactModel.h
/// @brief The contact model between two grains, assembled from its sub-models (as LAMMPS
///        GRANULAR assembles its normal, damping and tangential sub-models): the formulation's
///        normal law (NormalModel.h), a viscous dashpot on the contact's approach calibrated by
///        a coefficient of restitution (DampingModel.h) and per-node shear springs with
///        friction (TangentialModel.h), plus which nodes are tested. Units are the user's
///        (e.g. mm, N, s).
#pragma once

#include "lsdem/contact/DampingModel.h"
#include "lsdem/contact/NormalModel.h"
#include "lsdem/contact/PatchQuadrature.h"
#include "lsdem/contact/TangentialModel.h"

#include <string>

namespace lsdem {

/// Which grain's nodes are tested against the other's level set.
enum class NodeTesting {
    OneWay,     ///< the smaller grain's nodes (by bounding radius; ties: the lower index)
    Symmetric,  ///< both grains' nodes, each direction at half weight
};

struct ContactModel
{
    Formulation formulation = Formulation::Adapted;
    NodeTesting testing = NodeTesting::Symmetric;
    /// Each node as a point (the paper's rule) or as its patch (PatchQuadrature.h).
    NodeQuadrature quadrature = NodeQuadrature::Point;
    double normalStiffness = 0.0;  ///< kn or kn* (normal().stiffnessUnit())
    double shearStiffness = 0.0;   ///< ks (force/length) or ks* (force/length³), per node
    double friction = 0.0;         ///< Coulomb coefficient μ
    /// The dashpot, from the coefficient of restitution e of an impact (default 1: none):
    /// ContactModel::damping = ViscousDamping(e).
    ViscousDamping damping;

    const NormalModel& normal() const { return normalModel(formulation); }
    ShearSpringModel tangential() const { return {shearStiffness, friction}; }
};

std::string nodeTestingName(NodeTesting t);
/// Inverse of nodeTestingName. @throw Error naming the accepted values.
NodeTesting parseNodeTesting(const std::string& name);

/// normalModel(f).stiffnessUnit().
std::string stiffnessUnit(Formulation f);

} // namespace lsdem

/// @file NormalForce.h
/// @brief The normal contact laws, one per formulation, all fed the same penetrating nodes.
///        Each turns the nodes of grain A inside grain B into forces on A (B gets the
///        opposite), applied at points, so torques follow from the same list.
#pragma once

#include "lsdem/contact/ContactModel.h"
#include "lsdem/contact/NodeContact.h"

#include <vector>

namespace lsdem {

/// A force on grain A at a world point; @a node is the node it came from (-1 if pooled).
struct PointForce
{
    int node = -1;
    Vec3 force = Vec3::Zero();
    Vec3 point = Vec3::Zero();
    /// dF/dd of the normal law that made it (force/length): for contact damping, the
    /// elastic energy ½|F|²/k and the stable time step.
    double stiffness = 0.0;
};

/// kn·d_a·n_a at each node (original LS-DEM, Kawamoto et al. 2016).
void normalForcesOriginal(const std::vector<NodeContact>& contacts, double kn, double weight,
                          std::vector<PointForce>& out);

/// kn*·d_a·A_a·n_a at each node: the nodes are quadrature points of the traction kn*·d
/// (Feldfogel et al. 2024).
void normalForcesAdapted(const std::vector<NodeContact>& contacts, double knStar, double weight,
                         std::vector<PointForce>& out);

/// kn·d_max·n at the deepest node only (Li et al. 2019; YADE's default LS contact).
void normalForcesSingleNode(const std::vector<NodeContact>& contacts, double kn, double weight,
                            std::vector<PointForce>& out);

/// kv·V·n̄ with the overlap volume V ≈ Σ d_a·A_a, the direction n̄ of Σ d_a·A_a·n_a and the
/// point at the d·A-weighted centroid of the nodes (after van der Haven et al. 2023).
void normalForcesVolume(const std::vector<NodeContact>& contacts, double kv, double weight,
                        std::vector<PointForce>& out);

/// Dispatch on @a formulation. @a weight scales the stiffness (1/2 in symmetric testing).
void normalForces(Formulation formulation, const std::vector<NodeContact>& contacts,
                  double stiffness, double weight, std::vector<PointForce>& out);

} // namespace lsdem

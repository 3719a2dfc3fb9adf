/// @file NormalModel.h
/// @brief The normal contact law of each formulation as one small sub-model (in the manner of
///        LAMMPS GRANULAR's normal sub-models). It knows its name, the unit of its stiffness,
///        whether that stiffness is per unit area, whether its forces are per node (and so can
///        carry per-node shear springs), the stiffness the paper uses, and how it turns the
///        penetrating nodes of grain A inside grain B into point forces on A (B gets the
///        opposite). The laws, the time step, the scene reader and the studies all ask it.
#pragma once

#include "lsdem/contact/NodeContact.h"
#include "lsdem/contact/PointForce.h"

#include <optional>
#include <string>
#include <vector>

namespace lsdem {

/// How the penetrating nodes of a contact become a force (SCIENCE.md §2).
enum class Formulation {
    Original,    ///< F_a = kn·d_a·n_a per node; kn in force/length
    Adapted,     ///< F_a = kn*·d_a·A_a·n_a per node; kn* in force/length³ (traction/length)
    SingleNode,  ///< one force kn·d_max·n from the deepest node; kn in force/length
    Volume,      ///< F = kv·V·n̄ with V = Σ d_a·A_a; kv in force/length³
};

class NormalModel
{
public:
    virtual ~NormalModel() = default;

    virtual Formulation formulation() const = 0;
    /// "original", "adapted", "single-node", "volume".
    virtual std::string name() const = 0;
    /// The unit of its stiffness, in words ("force/length", ...).
    virtual std::string stiffnessUnit() const = 0;
    /// The unit of its stiffness in @a force and @a length units: "N/mm" for a spring per
    /// node, "N/mm³" per unit area (or overlap volume).
    std::string stiffnessUnitIn(const std::string& force, const std::string& length) const
    {
        return force + "/" + length + (stiffnessPerArea() ? "³" : "");
    }
    /// Whether the stiffness is per unit area (a traction per penetration, or a force per
    /// overlap volume): a node of tributary area A then stands for k·A.
    virtual bool stiffnessPerArea() const = 0;
    /// Whether every penetrating node gets a force of its own (so it may carry a shear spring).
    /// If so, forces() gives each contact i exactly one point force, in the contacts' order:
    /// k_i·d_i·n_i with stiffness k_i (d_i > 0 its depth, n_i its unit normal, k_i a linear
    /// spring). The contact law relies on that (resolveContact reads |F| = k_i·d_i and n_i
    /// from the contact).
    virtual bool perNodeForces() const = 0;
    /// Whether its nodes may be integrated over their patches (PatchQuadrature.h): a traction
    /// per area with a force per node (the adapted law). The original law's spring per node
    /// has no traction to integrate.
    bool integratesPatches() const { return stiffnessPerArea() && perNodeForces(); }
    /// The stiffness of the paper's studies (Feldfogel et al. 2024): kn = 1 GN/mm per node,
    /// kn* = 1 GPa/mm = 1e3 N/mm³ per area (in mm, N).
    virtual double paperStiffness() const = 0;

    /// The stiffness one node of tributary area @a area brings (force/length): k·A per area,
    /// k per node.
    double nodeStiffness(double stiffness, double area) const
    {
        return nodeStiffness(stiffnessPerArea(), stiffness, area);
    }
    /// The same for a law whose stiffnessPerArea() is @a perArea (asked once, not per node).
    static double nodeStiffness(bool perArea, double stiffness, double area)
    {
        return perArea ? stiffness * area : stiffness;
    }
    /// The normal stiffness (force/length) of a flat patch of area @a area in full contact,
    /// covered by nodes of tributary area @a nodeArea each: the integral of the traction for
    /// the per-area laws, one spring per node for the original law, one spring for the
    /// single-node law.
    virtual double patchStiffness(double stiffness, double area, double nodeArea) const = 0;

    /// Whether, at a fixed stiffness, the law's forces converge as the nodes refine (to the
    /// traction integral of continuumSphereForce and its kin): the laws per area do; the
    /// original law grows with the node count, the single-node law samples one node.
    bool convergesWithNodes() const { return stiffnessPerArea(); }
    /// The traction per penetration (force/length³) the law acts like when its nodes have the
    /// mean tributary area @a nodeArea: the stiffness itself for the laws per area, kn/A for
    /// the original law (each node's spring spread over its area). None for a law whose
    /// force does not grow with the contact's area (single-node: one spring).
    virtual std::optional<double> tractionStiffness(double stiffness, double nodeArea) const = 0;
    /// The inverse: the stiffness of this law that acts like the traction stiffness
    /// @a traction with nodes of mean area @a nodeArea (none where tractionStiffness has none).
    virtual std::optional<double> stiffnessForTraction(double traction, double nodeArea) const = 0;
    /// The force between two equal spheres of radius @a radius overlapping by @a overlap in
    /// the law's continuum limit, at traction stiffness @a traction (SphereContactReference.h):
    /// the traction integral projected on the centre line; the volume law's own integral (no
    /// projection). For a sphere on a plane both are exactly π·k·R·d².
    virtual double continuumSphereForce(double radius, double overlap, double traction) const;

    /// Append the point forces of the penetrating nodes @a contacts of A in B, for stiffness
    /// @a stiffness scaled by @a weight (1/2 per side in symmetric testing). A per-node law
    /// must keep the contract of perNodeForces().
    virtual void forces(const std::vector<NodeContact>& contacts, double stiffness,
                        double weight, std::vector<PointForce>& out) const = 0;

    /// The elastic energy of the forces() of the same arguments (when they are not empty): the
    /// potential whose derivative along the depths they are. Here ½·w·Σ k_a·d_a², k_a the
    /// node stiffness: each node's spring for the per-node laws (whose energy resolveContact
    /// sums node by node instead), and for the volume law, whose force kv·Σ A_a·d_a is that
    /// sum's derivative (½|F|²/K with K = kv·Σ A_a would hold for a flat patch only: on a
    /// sphere's cap it misses a quarter). The single-node law overrides it.
    virtual double elasticEnergy(const std::vector<NodeContact>& contacts, double stiffness,
                                 double weight) const;
};

/// The sub-model of @a formulation (one shared, immutable instance each).
const NormalModel& normalModel(Formulation formulation);

/// Every formulation, in a fixed order (original, adapted, single-node, volume).
const std::vector<Formulation>& allFormulations();

/// The names of the formulations whose sub-model answers yes to @a property, in the order of
/// allFormulations(), each between @a quote marks, for messages: "original or adapted" for
/// &NormalModel::perNodeForces.
std::string formulationNamesWhere(bool (NormalModel::*property)() const,
                                  const std::string& quote = "");

/// normalModel(f).name().
std::string formulationName(Formulation f);
/// Inverse of formulationName. @throw Error naming the accepted values.
Formulation parseFormulation(const std::string& name);

} // namespace lsdem

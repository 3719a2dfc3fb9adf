#include "lsdem/simulation/StableStep.h"

#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetSampler.h"
#include "lsdem/simulation/World.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

namespace lsdem {

namespace {

double largestEigenvalue(const Mat3& m)
{
    Eigen::SelfAdjointEigenSolver<Mat3> solver;
    solver.computeDirect(m, Eigen::EigenvaluesOnly);
    return std::max(0.0, solver.eigenvalues().maxCoeff());
}

/// An upper bound on the largest eigenvalue of a symmetric positive semidefinite 3×3 matrix,
/// without its eigenvalues: the least of its Frobenius norm and Gershgorin's largest row sum.
/// Exact for a diagonal matrix (dashpots along the axes), at most √3 times the eigenvalue.
double largestEigenvalueBound(const Mat3& m)
{
    return std::max(0.0, std::min(m.norm(), m.cwiseAbs().rowwise().sum().maxCoeff()));
}

/// An upper bound on the largest eigenvalue of a symmetric 3×3 matrix, also without its
/// eigenvalues but close to it where the eigenvalues are close (a grain held by several
/// contacts, each with shear springs: there the Frobenius norm is up to √3 times over): the
/// least of largestEigenvalueBound and the traces' bound of Wolkowicz & Styan (Linear Algebra
/// Appl. 29, 1980) for n = 3, λ_max ≤ m + √2·s with m = tr A/3 and s² = tr A²/3 − m², which is
/// exact where the two smaller eigenvalues are equal. Round-off must not take it below the
/// eigenvalue as largestEigenvalue computes it: the 1e-12·tr A²/3 added to s² covers s²'s
/// (about 1e-16 of tr A², which its root makes 1e-8), and the factor 1 + 1e-12 the ties where
/// a bound is exact (Gershgorin's for a diagonal matrix, Frobenius's for one contact).
double largestEigenvalueTraceBound(const Mat3& m)
{
    const double mean = m.trace() / 3.0;
    const double meanSquare = m.squaredNorm() / 3.0;  // tr A²/3, A symmetric
    const double spread2 = std::max(0.0, meanSquare - mean * mean) + 1e-12 * meanSquare;
    const double traces = std::max(0.0, mean + std::sqrt(2.0 * spread2));
    return (1.0 + 1e-12) * std::min(largestEigenvalueBound(m), traces);
}

/// The nodes of a grain that a flat wall square to @a direction (asset frame, outward) meets
/// first: those within @a band of its support plane.
std::vector<int> bandNodes(const SurfaceNodes& nodes, const Vec3& direction, double band)
{
    double support = -std::numeric_limits<double>::infinity();
    for (const Vec3& p : nodes.positions) support = std::max(support, p.dot(direction));
    std::vector<int> band_;
    for (size_t k = 0; k < nodes.size(); ++k)
        if (nodes.positions[k].dot(direction) >= support - band) band_.push_back(int(k));
    return band_;
}

/// The walls of automaticTimeStep for @a asset: its principal axes, both ways, and the outward
/// level-set normals at up to 256 of its nodes.
std::vector<Vec3> wallDirections(const GrainAsset& asset)
{
    std::vector<Vec3> directions;
    for (int axis = 0; axis < 3; ++axis)
        for (double sign : {1.0, -1.0}) directions.push_back(sign * Vec3::Unit(axis));
    const size_t n = asset.nodes.size();
    if (!asset.levelSet || n == 0) return directions;
    LevelSetSampler sampler(*asset.levelSet);
    const size_t stride = std::max<size_t>(1, (n + 255) / 256);
    for (size_t k = 0; k < n; k += stride) {
        const Vec3 gradient = sampler.sample(asset.nodes.positions[k]).gradient;
        if (gradient.norm() > 0.5) directions.push_back(gradient.normalized());
    }
    return directions;
}

/// The contact of a wall square to @a direction against the nodes @a band of @a asset, under
/// @a model, as the stability check sums it (asset frame, about the centroid at the origin).
GrainStiffness wallContactStiffness(const GrainAsset& asset, const std::vector<int>& band,
                                    const Vec3& direction, const ContactModel& model)
{
    GrainStiffness k;
    const NormalModel& law = model.normal();
    const Mat3 identity = Mat3::Identity();
    const Mat3 across = identity - direction * direction.transpose();
    if (law.perNodeForces()) {
        const bool shear = model.tangential().active(law);
        for (int node : band) {
            const double area = asset.nodes.areas[size_t(node)];
            const double kn = law.nodeStiffness(model.normalStiffness, area);
            const double kt = shear ? law.nodeStiffness(model.shearStiffness, area) : 0.0;
            const Vec3& r = asset.nodes.positions[size_t(node)];
            const Vec3 w = r.cross(direction);
            Mat3 lever;
            lever << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
            k.translation += kn * direction * direction.transpose() + kt * across;
            k.rotation += kn * w * w.transpose() + kt * lever * across * lever.transpose();
        }
        return k;
    }
    // One force for the whole patch, at its area-weighted centre.
    double area = 0.0;
    Vec3 centre = Vec3::Zero();
    for (int node : band) {
        area += asset.nodes.areas[size_t(node)];
        centre += asset.nodes.areas[size_t(node)] * asset.nodes.positions[size_t(node)];
    }
    if (!(area > 0.0)) return k;
    centre /= area;
    const double meanArea = asset.nodes.totalArea() / double(asset.nodes.size());
    const double kn = law.patchStiffness(model.normalStiffness, area, meanArea);
    const Vec3 w = centre.cross(direction);
    k.translation = kn * direction * direction.transpose();
    k.rotation = kn * w * w.transpose();
    return k;
}

/// The distinct contact laws of @a world (the matrix of models repeats each pair twice).
std::vector<ContactModel> distinctModels(const World& world)
{
    std::vector<ContactModel> models;
    for (const ContactModel& m : world.models) {
        if (!(m.normalStiffness > 0.0)) continue;
        const bool seen = std::any_of(models.begin(), models.end(), [&](const ContactModel& o) {
            return o.formulation == m.formulation && o.normalStiffness == m.normalStiffness &&
                   o.shearStiffness == m.shearStiffness && o.friction == m.friction;
        });
        if (!seen) models.push_back(m);
    }
    return models;
}

} // namespace

namespace {

/// A grain's step limit for a highest mode ω² = @a omega2 and a damping rate @a rate under
/// global damping @a globalDamping (λ): dampedStableStep's, infinite without stiffness (a
/// grain's dashpots come with its springs). A simulation of one degree of freedom in the
/// step's order puts its limit at ω·dt = 2/√(1 + λ) undamped (1.754 at λ = 0.3) and at 1.0609
/// for λ = 0.3 and β = 0.46, where this gives 1.0607.
double dampedLimit(double omega2, double rate, double globalDamping)
{
    if (!(omega2 > 0.0)) return std::numeric_limits<double>::infinity();
    return dampedStableStep(omega2, rate, globalDamping);
}

/// λ_max(T)/m + λ_max(I^-½ Rᵀ R_w R I^-½) of @a body for a translational block @a translation
/// and a rotational one @a rotation (world frame): the bound of StableStep.h on the largest
/// eigenvalue of the 6×6 mass-scaled matrix, stiffness or damping, each block's λ_max taken by
/// @a largest (largestEigenvalue, or largestEigenvalueBound where a bound will do).
template <class Largest>
double massScaledBound(const Mat3& translation, const Mat3& rotation, const RigidBody& body,
                       Largest largest)
{
    double bound = largest(translation) / body.mass;
    // Exactly zero: Eigen's isZero() would compare each entry with 1e-12, which in small units
    // (fine grains in SI) drops a rotational stiffness that sets the step.
    if (!rotation.isZero(0.0)) {
        // In the principal frame, scaled by 1/sqrt(I_k) on both sides.
        const Mat3 turn = body.pose.orientation.toRotationMatrix();
        const Vec3 scale = body.principalInertia.cwiseSqrt().cwiseInverse();
        const Mat3 bodyFrame = turn.transpose() * rotation * turn;
        bound += largest(Mat3(scale.asDiagonal() * bodyFrame * scale.asDiagonal()));
    }
    return bound;
}

/// The same bound without eigenvalues, from the traces (largestEigenvalueTraceBound), and
/// lambda_max(I^-1/2 R^T K R I^-1/2) <= lambda_max(K) / I_min.
double massScaledTraceBound(const Mat3& translation, const Mat3& rotation, const RigidBody& body)
{
    return largestEigenvalueTraceBound(translation) / body.mass +
           largestEigenvalueTraceBound(rotation) / body.principalInertia.minCoeff();
}

/// The same bound from Frobenius norms: lambda_max(K) <= |K|_F, and
/// lambda_max(I^-1/2 R^T K R I^-1/2) <= lambda_max(K) / I_min.
double massScaledFrobeniusBound(const Mat3& translation, const Mat3& rotation,
                                const RigidBody& body)
{
    return translation.norm() / body.mass + rotation.norm() / body.principalInertia.minCoeff();
}

/// The damping rate a step must allow for: each contact's ratio on the fastest mode, or the
/// summed dashpots' rate @a summedRate, whichever is larger.
double dampingRate(double omega2, double dampingRatio, double summedRate)
{
    return std::max(2.0 * std::max(0.0, dampingRatio) * std::sqrt(std::max(0.0, omega2)),
                    summedRate);
}

} // namespace

double stableStep(const GrainStiffness& stiffness, const RigidBody& body, double dampingRatio,
                  double globalDamping)
{
    const double omega2 =
        massScaledBound(stiffness.translation, stiffness.rotation, body, largestEigenvalue);
    // The dashpots' sum by a bound without eigenvalues: the check runs for most grains at every
    // step, and two more eigenvalue problems a grain cost 5 % of a lattice's step.
    const double summedRate = massScaledBound(stiffness.translationDamping,
                                              stiffness.rotationDamping, body,
                                              largestEigenvalueBound);
    return dampedLimit(omega2, dampingRate(omega2, dampingRatio, summedRate), globalDamping);
}

double stableStepLowerBound(const GrainStiffness& stiffness, const RigidBody& body,
                            double dampingRatio, double globalDamping)
{
    // No springs: any step (as below, where ω² = 0), for most grains of a loose packing.
    if (stiffness.translation.isZero(0.0) && stiffness.rotation.isZero(0.0))
        return std::numeric_limits<double>::infinity();
    const double omega2 = massScaledTraceBound(stiffness.translation, stiffness.rotation, body);
    const double summedRate = massScaledFrobeniusBound(stiffness.translationDamping,
                                                       stiffness.rotationDamping, body);
    return dampedLimit(omega2, dampingRate(omega2, dampingRatio, summedRate), globalDamping);
}

double largestDampingRatio(const World& world)
{
    double largest = 0.0;
    for (const ContactModel& m : world.models)
        largest = std::max(largest, m.damping.largestRatio());
    return largest;
}

std::vector<double> stiffestContactSteps(const World& world)
{
    const std::vector<ContactModel> models = distinctModels(world);
    const double beta = largestDampingRatio(world);
    // Per asset, the stiffness of each wall under each model (in its principal frame).
    std::map<const GrainAsset*, std::vector<GrainStiffness>> walls;
    // A grain's steps depend on its asset, mass and principal moments alone: grains of one
    // asset and material (most of a scene's) share one result, computed once. Each is a few
    // hundred walls' eigenvalues: grain by grain, 1000 spheres took 32 ms, 100,000 would take
    // seconds (and `time_step = "auto"` forecasts twice).
    using Body = std::tuple<const GrainAsset*, double, double, double, double>;
    std::map<Body, double> stepOf;
    std::vector<double> steps(world.grains.size(), std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < world.grains.size(); ++i) {
        const Grain& g = world.grains[i];
        if (!g.isFree()) continue;
        const GrainAsset& asset = *g.asset;
        const Vec3& moments = g.body.principalInertia;
        const Body body{&asset, g.body.mass, moments.x(), moments.y(), moments.z()};
        if (const auto known = stepOf.find(body); known != stepOf.end()) {
            steps[i] = known->second;
            continue;
        }
        auto found = walls.find(&asset);
        if (found == walls.end()) {
            std::vector<GrainStiffness> stiffnesses;
            const double band = kAutomaticBandFraction * asset.boundingRadius;
            for (const Vec3& d : wallDirections(asset)) {
                const std::vector<int> nodes = bandNodes(asset.nodes, d, band);
                for (const ContactModel& m : models)
                    stiffnesses.push_back(wallContactStiffness(asset, nodes, d, m));
            }
            found = walls.emplace(&asset, std::move(stiffnesses)).first;
        }
        RigidBody principal = g.body;  // the walls are in the asset's (principal) frame
        principal.pose.orientation = Quat::Identity();
        for (const GrainStiffness& k : found->second) {
            // A partner that moves as much doubles the stiffness the grain feels.
            const GrainStiffness doubled{2.0 * k.translation, 2.0 * k.rotation};
            steps[i] = std::min(steps[i], stableStep(doubled, principal, beta, world.globalDamping));
        }
        stepOf.emplace(body, steps[i]);
    }
    return steps;
}

double stiffestMembraneContact(const World& world, const Membrane& m)
{
    double lightest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < m.positions.size(); ++i)
        if (m.heldBy[i] < 0) lightest = std::min(lightest, m.masses[i]);
    if (!std::isfinite(lightest)) return 0.0;  // every vertex held: walls
    const double massPerArea = m.rubber.density * m.rubber.thickness;
    double omega2 = 0.0;
    std::set<std::pair<const GrainAsset*, int>> seen;  // (asset, material): one look each
    for (const Grain& g : world.grains) {
        if (!g.isFree() || !seen.emplace(g.asset.get(), g.material).second)
            continue;
        const ContactModel& model = world.model(g.material, m.material);
        if (!(model.normalStiffness > 0.0) || g.asset->nodes.size() == 0) continue;
        const double nodeArea = g.asset->nodes.totalArea() / double(g.asset->nodes.size());
        const std::optional<double> traction =
            model.normal().tractionStiffness(model.normalStiffness, nodeArea);
        const double vertex = traction ? *traction / massPerArea : model.normalStiffness / lightest;
        omega2 = std::max(omega2, 2.0 * vertex);
    }
    return omega2;
}

double stiffestMembraneContactStep(const World& world, const Membrane& m,
                                   double rubberOmegaSquared)
{
    const double contact = stiffestMembraneContact(world, m);
    const double rate =
        membraneDragRate(m) + 2.0 * largestDampingRatio(world) * std::sqrt(contact);
    return dampedStableStep(rubberOmegaSquared + contact, rate, world.globalDamping);
}

double automaticTimeStep(const World& world, double safety)
{
    double step = std::numeric_limits<double>::infinity();
    for (const double s : stiffestContactSteps(world)) step = std::min(step, s);
    for (const Membrane& m : world.membranes)
        step = std::min(step, stiffestMembraneContactStep(world, m, membraneRubberOmegaSquared(m)));
    if (!std::isfinite(step))
        throw Error("", "cannot choose an automatic time step: no free grain or no contact stiffness",
                    "give [simulation] time_step explicitly");
    return safety * step;
}

} // namespace lsdem

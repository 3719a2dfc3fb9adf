// The cases of the reference-force files, posed by hand so that every kind of contact is
// generic (tilted, off-centre, closing, sliding and spinning bodies, moving boundaries), and
// the plausibility checks run when the files are regenerated (see ReferenceForces.h).
#include "libcontact/contact/ReferenceForces.h"

#include "lsdem/core/Constants.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lsdem::test::reference {

namespace {

constexpr double kDt = 2e-4;
constexpr double kSphereMass = 0.004, kBoxMass = 0.015;
constexpr double kRadius = 1.0;  // of the "sphere" asset
/// Boundaries start displaced by this, so that their displacement is part of what is tested.
const Vec3 kMoved(0.01, 0.02, 0.03);

Quat turn(double angle, const Vec3& axis)
{
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

/// Stiffnesses that give forces of a few tens for the poses below; shear, friction and damping
/// on for every formulation (single-node and volume carry no shear: their springs stay idle).
ContactModel modelFor(Formulation f, NodeTesting testing)
{
    ContactModel m;
    m.formulation = f;
    m.testing = testing;
    switch (f) {
    case Formulation::Original: m.normalStiffness = 25.0; m.shearStiffness = 20.0; break;
    case Formulation::Adapted: m.normalStiffness = 1e3; m.shearStiffness = 800.0; break;
    case Formulation::SingleNode: m.normalStiffness = 400.0; m.shearStiffness = 300.0; break;
    case Formulation::Volume: m.normalStiffness = 1e3; m.shearStiffness = 800.0; break;
    }
    m.friction = 0.4;
    m.damping = ViscousDamping(0.55);
    return m;
}

/// The state one step later: the bodies moved at their velocities (turned about fixed axes),
/// the boundary displaced.
Evaluation advanced(const Evaluation& e)
{
    Evaluation next = e;
    for (BodyState* s : {&next.first, &next.second}) {
        s->pose.position += s->velocity * e.dt;
        const double angle = s->angularVelocity.norm() * e.dt;
        if (angle > 0.0)
            s->pose.orientation =
                (turn(angle, s->angularVelocity) * s->pose.orientation).normalized();
    }
    next.boundaryDisplacement += e.boundaryVelocity * e.dt;
    return next;
}

/// The box first and the sphere second, 0.08 into the box's +x face off its centre, closing and
/// sliding. One-way testing then tests the smaller sphere's nodes, i.e. the second grain's.
Case grainPair(Formulation f, NodeTesting testing)
{
    Case c;
    c.kind = testing == NodeTesting::OneWay ? "grain-grain-one-way" : "grain-grain-symmetric";
    c.model = modelFor(f, testing);
    c.firstAsset = "box";
    c.firstMass = kBoxMass;
    c.secondAsset = "sphere";
    c.secondMass = kSphereMass;
    Evaluation e;
    e.dt = kDt;
    e.first.pose.position = Vec3(0.2, -0.1, 0.3);
    e.first.pose.orientation = turn(0.5, Vec3(1, 2, -1));
    e.first.velocity = Vec3(1, 2, -1);
    e.first.angularVelocity = Vec3(0.5, -1, 2);
    const Quat& q = e.first.pose.orientation;
    e.second.pose.position = e.first.pose.position + q * Vec3(1.0 + kRadius - 0.08, 0.1, 0.05);
    e.second.pose.orientation = turn(1.3, Vec3(-2, 1, 3));
    e.second.velocity = q * Vec3(-20, 30, 10);
    e.second.angularVelocity = Vec3(4, -3, 6);
    c.evaluations = {e, advanced(e)};
    return c;
}

/// The sphere grain against a boundary, closing, sliding and spinning.
Case grainBoundary(Formulation f, const std::string& kind)
{
    Case c;
    c.kind = kind;
    c.model = modelFor(f, NodeTesting::OneWay);  // one side either way
    c.firstAsset = "sphere";
    c.firstMass = kSphereMass;
    Evaluation e;
    e.dt = kDt;
    e.first.pose.orientation = turn(0.9, Vec3(1, 1, 1));
    e.first.angularVelocity = Vec3(3, -5, 8);
    e.boundaryDisplacement = kMoved;
    Boundary& b = c.boundary;
    if (kind == "grain-plane" || kind == "grain-patch") {
        // A tilted plane through `point` (after its displacement), rising along its normal; the
        // sphere 0.1 behind it, 0.1 off the point along u.
        const Vec3 n = Vec3(0.1, -0.2, 1).normalized();
        const Vec3 u = (Vec3::UnitX() - n.x() * n).normalized();
        const Vec3 point(0.3, -0.2, 0.1);
        b.shape = BoundaryShape::Plane;
        b.plane.point = point - kMoved;
        b.plane.normal = n;
        b.plane.axisU = u;
        e.boundaryVelocity = Vec3(0.5, -1.0, 4.0);
        e.first.pose.position = point + (kRadius - 0.1) * n + 0.1 * u;
        e.first.velocity = -20 * n + 30 * u + Vec3(0, 5, 0);
        if (kind == "grain-patch") {
            // The patch's edge at u = 0.15 cuts the contact cap (radius 0.45) and only nodes
            // less than 0.07 behind it count (the cap is 0.1 deep).
            b.plane.halfU = 0.15;
            b.plane.halfV = 0.6;
            b.plane.thickness = 0.07;
        }
    } else if (kind == "grain-sphere") {
        // An indenter of radius 0.6 pressed 0.08 into the grain and moving toward it.
        const Vec3 m = Vec3(0.3, 0.9, -0.2).normalized();
        const Vec3 centre(-0.5, 0.4, 0.2);
        b.shape = BoundaryShape::Sphere;
        b.center = centre - kMoved;
        b.radius = 0.6;
        e.boundaryVelocity = 10 * m;
        e.first.pose.position = centre + (kRadius + 0.6 - 0.08) * m;
        e.first.velocity = Vec3(8, -2, 5) - 5 * m;
    } else {
        // The box as an obstacle, turned; the sphere 0.09 into its top face, over its +x edge.
        const Vec3 position(-0.4, 0.2, 0.5);
        c.secondAsset = "box";
        b.shape = BoundaryShape::LevelSet;
        b.asset = std::shared_ptr<const GrainAsset>(&referenceAsset("box"),
                                                    [](const GrainAsset*) {});  // not owned
        b.pose.position = position - kMoved;
        b.pose.orientation = turn(0.8, Vec3(0, 1, 1));
        e.boundaryVelocity = Vec3(1, 0, -2);
        const Quat& q = b.pose.orientation;
        e.first.pose.position = position + q * Vec3(0.85, -0.2, 0.6 + kRadius - 0.09);
        e.first.velocity = q * Vec3(10, 5, -20);
        e.first.angularVelocity = Vec3(1, 2, -4);
    }
    c.evaluations = {e, advanced(e)};
    return c;
}

std::string fixed(double v, int digits = 3)
{
    std::ostringstream s;
    s.precision(digits);
    s << v;
    return s.str();
}

/// The case's first state at rest, without shear or damping: the elastic force alone.
Outcome elasticOnly(const Case& c)
{
    Case s = c;
    s.model.shearStiffness = s.model.friction = 0.0;
    s.model.damping = ViscousDamping();
    Evaluation e = c.evaluations[0];
    e.first.velocity = e.first.angularVelocity = Vec3::Zero();
    e.second.velocity = e.second.angularVelocity = Vec3::Zero();
    e.boundaryVelocity = Vec3::Zero();
    s.evaluations = {e};
    return evaluate(s)[0];
}

/// ∫ d (n·e) dA and ∫ d dA over the part of a sphere (radius R) inside a rigid sphere (radius
/// Ri) whose centre is h away: with u = cos θ on the grain, ρ = sqrt(R² + h² - 2Rhu),
/// d = Ri - ρ, n·e = (h - Ru)/ρ, dA = 2πR² du (composite Simpson, 2000 intervals).
std::pair<double, double> indenterIntegrals(double r, double ri, double h)
{
    const double u0 = (r * r + h * h - ri * ri) / (2 * r * h);
    const int n = 2000;
    double projected = 0.0, plain = 0.0;
    for (int k = 0; k <= n; ++k) {
        const double u = u0 + (1.0 - u0) * k / n;
        const double rho = std::sqrt(r * r + h * h - 2 * r * h * u);
        const double weight = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
        projected += weight * (ri - rho) * (h - r * u) / rho;
        plain += weight * (ri - rho);
    }
    const double scale = 2 * kPi * r * r * (1.0 - u0) / (3.0 * n);
    return {scale * projected, scale * plain};
}

} // namespace

std::vector<Case> generateCases(Formulation f)
{
    std::vector<Case> cases = {grainPair(f, NodeTesting::OneWay),
                               grainPair(f, NodeTesting::Symmetric)};
    for (const char* kind : {"grain-plane", "grain-patch", "grain-sphere", "grain-level-set"})
        cases.push_back(grainBoundary(f, kind));
    for (Case& c : cases) {
        c.expected = evaluate(c);
        // A node within round-off of a surface could flip in or out of contact on another
        // machine: the poses keep every node well clear.
        for (const Evaluation& e : c.evaluations)
            EXPECT_GT(contactMargin(c, e), 1e-6) << c.kind << ": move the pose";
    }
    return cases;
}

namespace {

/// Newton's third law and the balance of moments, in every evaluation of @a cases: two lines.
std::vector<std::string> balanceChecks(const std::vector<Case>& cases)
{
    double worstForce = 0.0, worstMoment = 0.0;
    int fewest = 1 << 30, most = 0;
    for (const Case& c : cases)
        for (size_t k = 0; k < c.evaluations.size(); ++k) {
            const Outcome& o = c.expected[k];
            const Evaluation& e = c.evaluations[k];
            Vec3 second = e.second.pose.position;
            if (!isGrainPair(c)) {
                Boundary b = c.boundary;
                b.displacement = e.boundaryDisplacement;
                second = b.referencePoint();
            }
            const double scale = o.forceFirst.norm();
            const double lever = std::max({e.first.pose.position.norm(), second.norm(), 1.0});
            worstForce = std::max(worstForce, (o.forceFirst + o.forceSecond).norm() / scale);
            worstMoment = std::max(
                worstMoment, (o.torqueFirst + o.torqueSecond +
                              e.first.pose.position.cross(o.forceFirst) +
                              second.cross(o.forceSecond)).norm() / (scale * lever));
            fewest = std::min(fewest, o.nodes);
            most = std::max(most, o.nodes);
        }
    EXPECT_LT(worstForce, 1e-12);
    EXPECT_LT(worstMoment, 1e-12);
    EXPECT_GT(fewest, 0);
    return {"every evaluation: forces on the two bodies opposite (|F1 + F2|/|F1| = " +
                fixed(worstForce, 2) + "),",
            "  total moment about the origin zero (" + fixed(worstMoment, 2) + " relative), " +
                std::to_string(fewest) + " to " + std::to_string(most) + " penetrating nodes"};
}

/// A case's elastic force against the closed form of law @a f: the closed form's value, the
/// band its ratio must lie in, and its name; no value where none applies.
struct ClosedForm
{
    double expected = 0.0, low = 0.0, high = 0.0;
    std::string what;
};

/// The depth δ of case @a c, the direction n pushing its grain out, the force on that grain and
/// the share w of it one grain's nodes carry: what the closed forms need.
struct Contact
{
    double delta = 0.0;
    Vec3 n = Vec3::Zero();
    Vec3 onGrain = Vec3::Zero();
    double weight = 1.0;
};

Contact contactOf(const Case& c, const Outcome& elastic)
{
    Contact k;
    k.onGrain = elastic.forceFirst;
    if (isGrainPair(c)) {  // the sphere on a face of the box: a flat contact
        k.delta = 0.08;
        k.n = c.evaluations[0].first.pose.orientation * Vec3::UnitX();  // out of the box
        k.onGrain = elastic.forceSecond;
        k.weight = c.model.testing == NodeTesting::Symmetric ? 0.5 : 1.0;
    } else if (c.boundary.shape == BoundaryShape::Plane) {
        k.delta = 0.1;
        k.n = c.boundary.plane.normal;
    } else if (c.boundary.shape == BoundaryShape::Sphere) {
        k.delta = 0.08;
        k.n = (c.evaluations[0].first.pose.position - c.boundary.center - kMoved).normalized();
    } else {
        k.delta = 0.09;
        k.n = c.boundary.pose.orientation * Vec3::UnitZ();
    }
    return k;
}

ClosedForm closedFormOf(Formulation f, const Case& c, const Contact& contact, int nodes)
{
    const double k = c.model.normalStiffness, delta = contact.delta;
    // Flat contacts (plane, box face): ∫ d dA over the cap = π·R·δ², exactly for a plane;
    // the depth of a node of the cap is uniform on [0, δ] (Archimedes), so the mean is δ/2.
    const double capIntegral = kPi * kRadius * delta * delta;
    const bool flat = c.kind == "grain-plane" || isGrainPair(c);
    if (f == Formulation::SingleNode)  // the deepest nodes of a patch are beyond it
        return {k * delta, c.kind == "grain-patch" ? 0.5 : 0.8, 1.0 + 1e-9, "kn·δ"};
    if (c.kind == "grain-sphere" && f != Formulation::Original) {
        const auto [projected, plain] = indenterIntegrals(kRadius, 0.6, kRadius + 0.6 - 0.08);
        if (f == Formulation::Adapted) return {k * projected, 0.85, 1.15, "kn*·∫d(n·e)dA"};
        return {k * plain, 0.85, 1.15, "kv·∫d dA"};
    }
    if (flat && f == Formulation::Original)
        return {contact.weight * k * nodes * delta / 2, 0.8, 1.2, "w·kn·N·δ/2"};
    if (flat) return {k * capIntegral, 0.85, 1.15, "k·π·R·δ²"};
    if (f != Formulation::Original)  // patch and edge: part of the cap is missing
        return {k * capIntegral, 0.2, 1.0, "k·π·R·δ² (part of the cap)"};
    return {};
}

} // namespace

std::vector<std::string> plausibilityChecks(Formulation f, const std::vector<Case>& cases)
{
    std::vector<std::string> lines = {
        "(\"elastic part\": the first state at rest without shear and damping; n: the direction",
        "pushing the grain out; closed forms: k·π·R·δ² = k·∫d dA over a sphere's cap behind a",
        "flat face, exact for a plane; w·kn·N·δ/2 for N nodes with depths uniform on [0, δ]",
        "(Archimedes) at weight w; kn·δ for the deepest node; ∫d(n·e)dA the continuum",
        "integral for the indenter)"};
    const bool shear = f == Formulation::Original || f == Formulation::Adapted;
    for (const std::string& line : balanceChecks(cases)) lines.push_back(line);

    for (const Case& c : cases) {
        const Outcome elastic = elasticOnly(c);
        const Outcome& full = c.expected[0];
        std::string line = c.kind + ": |F| " + fixed(full.forceFirst.norm()) + ", elastic part " +
                           fixed(elastic.forceFirst.norm()) + " (" + std::to_string(elastic.nodes) +
                           " nodes)";
        // The second evaluation again without the first's shear history.
        Case fresh = c;
        fresh.evaluations = {c.evaluations[1]};
        const double history = (evaluate(fresh)[0].forceFirst - c.expected[1].forceFirst).norm() /
                               c.expected[1].forceFirst.norm();
        if (shear) {
            EXPECT_GT(history, 1e-6) << c.kind << ": the shear history should matter";
        } else {
            EXPECT_EQ(history, 0.0) << c.kind << ": no shear, so no history";
        }
        line += "; history moves eval 2 by " + fixed(100 * history, 2) + " %";

        const Contact contact = contactOf(c, elastic);
        const double along = contact.onGrain.dot(contact.n);
        EXPECT_GT(along, 0.9 * contact.onGrain.norm()) << c.kind << ": pushes the grain out";
        const ClosedForm form = closedFormOf(f, c, contact, elastic.nodes);
        if (form.expected > 0.0) {
            const double ratio = along / form.expected;
            EXPECT_GT(ratio, form.low) << c.kind << " against " << form.what;
            EXPECT_LT(ratio, form.high) << c.kind << " against " << form.what;
            lines.push_back(line);
            line = "  elastic force along n / " + form.what + " = " + fixed(ratio, 4);
        }
        lines.push_back(line);
    }
    return lines;
}

} // namespace lsdem::test::reference

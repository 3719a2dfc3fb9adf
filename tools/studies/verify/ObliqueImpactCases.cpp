// Chung & Ooi's tests 4–8 (oblique impacts and impacts with spin) for the laws with shear
// springs (original and adapted). Three references: the law computed point by point on the
// ball's own nodes (ShearFieldReference.h; tight: it checks lsdem's dynamics), the law's
// continuum limit on a fine lattice of the ball's surface (adapted: the physics the nodes
// converge to), and rigid-body theory, which holds in gross sliding whatever the tangential
// stiffness (the friction impulse is μ times the normal one).
#include "studies/verify/ObliqueImpact.h"
#include "studies/verify/NormalImpactReference.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/NumberText.h"

#include <algorithm>
#include <cmath>

namespace lsdem::verify {

void obliqueImpactOnWall(Context& c)
{
    const Setup& s = c.bodies.setup();
    const auto ball = c.bodies.sphere();
    const double speed = 3900.0, friction = 0.092, restitution = 0.98, radius = s.radius;
    const double mass = ballMass(c);
    std::vector<double> angles;
    for (int k = 1; k <= 17; ++k)
        if (!c.quick || k == 2 || k == 6 || k == 9 || k == 14) angles.push_back(5.0 * k * kPi / 180.0);
    for (const Formulation f : frictionalLaws(c)) {
        const ContactModel law = lawFor(f, s, *ball, friction, restitution);
        Series curve;
        curve.name = "oblique_wall_" + formulationName(f);
        curve.columns = {"angle_deg", "et", "et_nodes", "et_continuum", "et_rigid",
                         "spin", "spin_nodes", "spin_continuum", "spin_rigid"};
        for (const double angle : angles) {
            const Vec3 v(speed * std::sin(angle), 0, -speed * std::cos(angle));
            const Rebound r = ballOnWall(c, law, v, Vec3::Zero());
            const WallReferences ref = wallReferences(c, law, mass, v, Vec3::Zero());
            const ImpactOutcome rigid =
                rigidImpact(ballBody(mass, radius, v, Vec3::Zero(), Vec3(0, 0, -radius)),
                            wallBody(), Vec3::UnitZ(), restitution, friction);
            const double et = r.velocity.x() / v.x();
            curve.rows.push_back({angle * 180.0 / kPi, et, ref.nodes.velocity.x() / v.x(),
                                  ref.continuum.velocity.x() / v.x(),
                                  rigid.first.velocity.x() / v.x(), r.angularVelocity.y(),
                                  ref.nodes.angularVelocity.y(), ref.continuum.angularVelocity.y(),
                                  rigid.first.angularVelocity.y()});
            const std::string name = "oblique-wall " + degrees(angle);
            addThreeWay(c, name, f, "tangential restitution", "", et,
                        ref.nodes.velocity.x() / v.x(), ref.continuum.velocity.x() / v.x(),
                        ref.hasContinuum, 1.0);
            addThreeWay(c, name, f, "rebound spin·R", "mm/s", r.angularVelocity.y() * radius,
                        ref.nodes.angularVelocity.y() * radius,
                        ref.continuum.angularVelocity.y() * radius, ref.hasContinuum, v.x());
            if (clearlySliding(v.x(), -v.z(), friction, restitution))
                c.report.add({name, formulationName(f), "tangential restitution (rigid body)", "",
                              rigid.first.velocity.x() / v.x(), et, 1.0, kNodeTolerance,
                              "gross sliding: friction impulse μ·J_n whatever the springs"});
        }
        c.report.series.push_back(curve);
    }
}
void obliqueImpactAtNormalSpeed(Context& c)
{
    // Test 5: the normal speed fixed at 5 m/s, the tangential one swept; e 1, μ 0.3. Chung &
    // Ooi plot the contact point's rebound Ψ₂ = V'_ct/(μ·V'_n) and the spin R·ω'/(μ·V_n)
    // against Ψ₁ = V_t/(μ·V_n); gross sliding for Ψ₁ ≥ 7, where Ψ₂ = Ψ₁ − 7, R·ω'/(μV_n) = −5.
    const Setup& s = c.bodies.setup();
    const auto ball = c.bodies.sphere();
    const double normalSpeed = 5000.0, friction = 0.3, restitution = 1.0, radius = s.radius;
    const double mass = ballMass(c);
    const std::vector<double> psis = c.quick ? std::vector<double>{1.0, 4.0, 14.0}
                                             : std::vector<double>{0.2, 0.6, 1.0, 1.5, 2.0, 3.0, 4.0,
                                                                   5.0, 6.0, 8.0, 10.0, 14.0};
    for (const Formulation f : frictionalLaws(c)) {
        const ContactModel law = lawFor(f, s, *ball, friction, restitution);
        Series curve;
        curve.name = "oblique_normal_speed_" + formulationName(f);
        curve.columns = {"psi1", "psi2", "psi2_nodes", "psi2_continuum", "psi2_rigid",
                         "spin", "spin_nodes", "spin_continuum", "spin_rigid"};
        const double unit = friction * normalSpeed;
        for (const double psi : psis) {
            const Vec3 v(psi * unit, 0, -normalSpeed);
            const Rebound r = ballOnWall(c, law, v, Vec3::Zero());
            const WallReferences ref = wallReferences(c, law, mass, v, Vec3::Zero());
            const ImpactOutcome rigid =
                rigidImpact(ballBody(mass, radius, v, Vec3::Zero(), Vec3(0, 0, -radius)),
                            wallBody(), Vec3::UnitZ(), restitution, friction);
            const auto psi2 = [&](const Vec3& vel, const Vec3& spin) {
                return (vel.x() - radius * spin.y()) / (friction * vel.z());
            };
            const auto spinOf = [&](const Vec3& spin) { return radius * spin.y() / unit; };
            curve.rows.push_back({psi, psi2(r.velocity, r.angularVelocity),
                                  psi2(ref.nodes.velocity, ref.nodes.angularVelocity),
                                  psi2(ref.continuum.velocity, ref.continuum.angularVelocity),
                                  psi2(rigid.first.velocity, rigid.first.angularVelocity),
                                  spinOf(r.angularVelocity), spinOf(ref.nodes.angularVelocity),
                                  spinOf(ref.continuum.angularVelocity),
                                  spinOf(rigid.first.angularVelocity)});
            char label[64];
            std::snprintf(label, sizeof label, "oblique-normal-speed Ψ1=%g", psi);
            // Errors against Ψ₁: relative to the incoming tangential speed.
            addThreeWay(c, label, f, "Ψ2", "", psi2(r.velocity, r.angularVelocity),
                        psi2(ref.nodes.velocity, ref.nodes.angularVelocity),
                        psi2(ref.continuum.velocity, ref.continuum.angularVelocity),
                        ref.hasContinuum, psi);
            addThreeWay(c, label, f, "R·ω'/(μ·V_n)", "", spinOf(r.angularVelocity),
                        spinOf(ref.nodes.angularVelocity), spinOf(ref.continuum.angularVelocity),
                        ref.hasContinuum, psi);
            if (psi >= 14.0 && law.normal().stiffnessPerArea())
                c.report.add({label, formulationName(f), "Ψ2 (rigid body)", "",
                              psi2(rigid.first.velocity, rigid.first.angularVelocity),
                              psi2(r.velocity, r.angularVelocity), psi,
                              kNodeTolerance + 5.0 / 7.0 * 2.0 / 3.0 * r.maxOverlap / radius * 7.0 / psi,
                              "gross sliding: Ψ2 = Ψ1 − 7; lever R − 2δ/3"});
        }
        c.report.series.push_back(curve);
    }
}

} // namespace lsdem::verify

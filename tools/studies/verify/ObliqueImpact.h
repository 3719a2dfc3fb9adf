// What the oblique and spin impact cases share (ObliqueImpactCases.cpp, SpinImpactCases.cpp):
// a ball thrown at a wall or an immovable ball in lsdem, the references of that impact (the law
// on the ball's nodes, and its continuum limit), rigid-body theory's bodies, and the checks of
// a quantity against both references. Private to the verification suite.
#pragma once

#include "studies/verify/RigidBodyTheory.h"
#include "studies/verify/ShearFieldReference.h"
#include "studies/verify/VerifyCases.h"

#include <string>
#include <vector>

namespace lsdem::verify {

/// A ball's state after an impact.
struct Rebound
{
    Vec3 velocity = Vec3::Zero(), angularVelocity = Vec3::Zero();
    double maxOverlap = 0.0;
};

/// The references of one impact of the ball on a wall: the law on the ball's nodes, and (for
/// laws per area) on a lattice of its surface; steps a fifth of lsdem's.
struct WallReferences
{
    BallImpact nodes, continuum;
    bool hasContinuum = false;
};

/// The node reference's tolerance: the two step sizes (lsdem's velocity Verlet at a thousandth
/// of the contact, the reference's semi-implicit Euler at a fifth of that), 0.5 % of the scale.
constexpr double kNodeTolerance = 5e-3;
/// The continuum's tolerance: the node quadrature of the cap shifts when the contact starts,
/// ends and how hard it presses; the normal impact at this resolution bounds that by its
/// contact time's error, about 1 % (normal-wall), so the tangential outcome is checked to 1 %
/// of the incoming tangential speed.
constexpr double kLatticeTolerance = 0.01;

/// The laws of @a c that carry shear springs.
std::vector<Formulation> frictionalLaws(const Context& c);
/// "60°".
std::string degrees(double radians);
/// The steps of an impact at normal speed @a normalSpeed: a thousandth of the contact time of
/// the adapted law's continuum limit (powerLawImpact), whatever the tangential motion.
double impactStep(const Setup& s, double mass, double normalSpeed, bool quick);
/// A ball of the setup thrown at a wall (normal +z), or with @a partnerRadius at a ball of
/// that radius below it (Chung & Ooi test 8: taken as immovable, lsdem's spherical boundary),
/// with velocity @a v and spin @a w, under @a law: its state once it has left.
Rebound ballOnWall(Context& c, const ContactModel& law, const Vec3& v, const Vec3& w,
                   double partnerRadius = 0.0);
WallReferences wallReferences(Context& c, const ContactModel& law, double mass, const Vec3& v,
                              const Vec3& w, double partnerRadius = 0.0);
/// Rigid-body theory's ball (solid sphere) and immovable wall.
ImpactBody ballBody(double mass, double radius, const Vec3& v, const Vec3& w, const Vec3& lever);
ImpactBody wallBody();
double ballMass(Context& c);
/// Whether rigid-body theory slides throughout with margin: the slip, 3.5·μ·(1+e)·V_n to stop,
/// is at least 1/0.8 times that (near the threshold, the springs' compliance decides).
bool clearlySliding(double slip, double normalSpeed, double friction, double restitution);
/// Add the checks of a quantity against the node reference and the continuum.
void addThreeWay(Context& c, const std::string& name, Formulation f, const std::string& quantity,
                 const std::string& unit, double value, double nodes, double continuum,
                 bool hasContinuum, double scale);

} // namespace lsdem::verify

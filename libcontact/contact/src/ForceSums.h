// Small pieces the contact law's files share (private to lsdem_contact): points and moments in
// plain numbers (the per-node loops run them for every node in contact) and a point force's
// direction.
#pragma once

#include "lsdem/contact/ContactLaw.h"

namespace lsdem::contactlaw {

/// A point as three numbers. A Vec3 copied into a local may be stored in a 16- and an 8-byte
/// piece and then read back across both, which stalls until the stores complete.
struct Point3
{
    double x, y, z;
    explicit Point3(const Vec3& v) : x(v.x()), y(v.y()), z(v.z()) {}
};

/// @a sum += (p − c) × f, or −= with @a subtract; component by component, the same operations
/// as Eigen's cross product, which would go through memory and stall the sum reading it back.
inline void accumulateMoment(Vec3& sum, const Vec3& p, const Point3& c, const Vec3& f, bool subtract)
{
    const double rx = p.x() - c.x, ry = p.y() - c.y, rz = p.z() - c.z;
    const double mx = ry * f.z() - rz * f.y(), my = rz * f.x() - rx * f.z(),
                 mz = rx * f.y() - ry * f.x();
    if (subtract)
        sum = Vec3(sum.x() - mx, sum.y() - my, sum.z() - mz);
    else
        sum = Vec3(sum.x() + mx, sum.y() + my, sum.z() + mz);
}

/// The unit direction of point force @a f of a side: its contact's normal for a per-node law
/// (@a contact not null), else the force's own direction (zero for a zero force).
inline Vec3 directionOf(const PointForce& f, const NodeContact* contact)
{
    if (contact) return contact->normal;
    const double size = f.force.norm();
    return size > 0.0 ? Vec3(f.force / size) : Vec3::Zero();
}

/// The size of elastic point force @a f: k·d for a per-node law (@a contact not null: read
/// from the contact, without a root), else |f|.
inline double normalForceSize(const PointForce& f, const NodeContact* contact)
{
    return contact ? f.stiffness * contact->depth : f.force.norm();
}

} // namespace lsdem::contactlaw

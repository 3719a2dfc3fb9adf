#include "GrainPacking.h"

#include <stdexcept>

namespace lsdem::grainpacking {

namespace {

void putBody(Writer& out, const RigidBody& b)
{
    out.values(b.pose.position.data(), 3);
    out.values(b.pose.orientation.coeffs().data(), 4);
    out.values(b.velocity.data(), 3);
    out.values(b.angularMomentum.data(), 3);
}

void getBody(Reader& in, RigidBody& b)
{
    in.values(b.pose.position.data(), 3);
    in.values(b.pose.orientation.coeffs().data(), 4);
    in.values(b.velocity.data(), 3);
    in.values(b.angularMomentum.data(), 3);
}

void putDissipated(Writer& out, const DissipatedEnergy& d)
{
    out.number(d.friction).number(d.dashpot).number(d.globalDamping);
}

DissipatedEnergy getDissipated(Reader& in)
{
    DissipatedEnergy d;
    d.friction = in.number();
    d.dashpot = in.number();
    d.globalDamping = in.number();
    return d;
}

} // namespace

void putGrain(Writer& out, const Grain& g, int assetIndex)
{
    out.text(g.name);
    out.value(assetIndex);
    out.value(g.material);
    out.value(static_cast<int>(g.motion));
    putBody(out, g.body);
    out.value(g.body.mass);
    out.values(g.body.principalInertia.data(), 3);
    out.values(g.prescribedAngularVelocity.data(), 3);
    out.values(g.force.data(), 3);
    out.values(g.torque.data(), 3);
    putDissipated(out, g.dissipated);
    out.values(g.wrapShift.data(), 3);
}

Grain getGrain(Reader& in, const World& world)
{
    Grain g;
    g.name = in.text();
    const int asset = in.value<int>();
    if (asset < 0 || size_t(asset) >= world.assets.size())
        throw std::runtime_error("grain packing: no such asset");
    g.asset = world.assets[size_t(asset)];
    g.material = in.value<int>();
    g.motion = static_cast<GrainMotion>(in.value<int>());
    getBody(in, g.body);
    g.body.mass = in.value<double>();
    in.values(g.body.principalInertia.data(), 3);
    in.values(g.prescribedAngularVelocity.data(), 3);
    in.values(g.force.data(), 3);
    in.values(g.torque.data(), 3);
    g.dissipated = getDissipated(in);
    in.values(g.wrapShift.data(), 3);
    return g;
}

void putState(Writer& out, const Grain& g)
{
    putBody(out, g.body);
}

void getState(Reader& in, Grain& g)
{
    getBody(in, g.body);
}

void putHistory(Writer& out, const ShearHistory& h)
{
    out.count(h.size());
    for (const ShearHistory::Entry& e : h.entries()) {
        out.value(e.node);
        out.values(e.force.data(), 3);
        out.value(e.stiffness);
    }
}

void getHistory(Reader& in, ShearHistory& h, std::vector<ShearHistory::Entry>& buffer)
{
    buffer.resize(in.count(sizeof(int) + 4 * sizeof(double)));
    for (ShearHistory::Entry& e : buffer) {
        e.node = in.value<int>();
        in.values(e.force.data(), 3);
        e.stiffness = in.value<double>();
    }
    h.replaceWith(buffer);
}

} // namespace lsdem::grainpacking

#include "GrainPacking.h"

namespace lsdem::grainpacking {

namespace {

void putBody(Writer& out, const RigidBody& b)
{
    out.putDoubles(b.pose.position.data(), 3);
    out.putDoubles(b.pose.orientation.coeffs().data(), 4);
    out.putDoubles(b.velocity.data(), 3);
    out.putDoubles(b.angularMomentum.data(), 3);
}

void getBody(Reader& in, RigidBody& b)
{
    in.getDoubles(b.pose.position.data(), 3);
    in.getDoubles(b.pose.orientation.coeffs().data(), 4);
    in.getDoubles(b.velocity.data(), 3);
    in.getDoubles(b.angularMomentum.data(), 3);
}

} // namespace

void putGrain(Writer& out, const Grain& g, int assetIndex)
{
    out.putString(g.name);
    out.put(assetIndex);
    out.put(g.material);
    out.put(static_cast<int>(g.motion));
    putBody(out, g.body);
    out.put(g.body.mass);
    out.putDoubles(g.body.principalInertia.data(), 3);
    out.putDoubles(g.prescribedAngularVelocity.data(), 3);
    out.putDoubles(g.force.data(), 3);
    out.putDoubles(g.torque.data(), 3);
}

Grain getGrain(Reader& in, const World& world)
{
    Grain g;
    g.name = in.getString();
    const int asset = in.get<int>();
    if (asset < 0 || size_t(asset) >= world.assets.size())
        throw std::runtime_error("grain packing: no such asset");
    g.asset = world.assets[size_t(asset)];
    g.material = in.get<int>();
    g.motion = static_cast<GrainMotion>(in.get<int>());
    getBody(in, g.body);
    g.body.mass = in.get<double>();
    in.getDoubles(g.body.principalInertia.data(), 3);
    in.getDoubles(g.prescribedAngularVelocity.data(), 3);
    in.getDoubles(g.force.data(), 3);
    in.getDoubles(g.torque.data(), 3);
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
    out.put(static_cast<unsigned>(h.size()));
    for (const ShearHistory::Entry& e : h.entries()) {
        out.put(e.node);
        out.putDoubles(e.force.data(), 3);
    }
}

void getHistory(Reader& in, ShearHistory& h, std::vector<ShearHistory::Entry>& buffer)
{
    buffer.resize(in.get<unsigned>());
    for (ShearHistory::Entry& e : buffer) {
        e.node = in.get<int>();
        in.getDoubles(e.force.data(), 3);
    }
    h.replaceWith(buffer);
}

} // namespace lsdem::grainpacking

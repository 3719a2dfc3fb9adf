// A [[membranes]] entry's rules and the membrane it makes.
#include "lsdem/scene/MembraneKeys.h"

#include "lsdem/scene/MembraneStateCsv.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <cmath>
#include <limits>

namespace lsdem {

namespace {

std::optional<KeyProblem> positiveProblem(const char* key, double v)
{
    if (v > 0.0 && std::isfinite(v)) return std::nullopt;
    return KeyProblem{key, "must be > 0 (got " + numberText(v) + ")", "give a positive value"};
}

std::optional<KeyProblem> nonNegativeProblem(const char* key, double v)
{
    if (v >= 0.0 && std::isfinite(v)) return std::nullopt;
    return KeyProblem{key, "must be >= 0 (got " + numberText(v) + ")", "give a value >= 0"};
}

} // namespace

std::optional<KeyProblem> membraneProblem(const MembraneSpec& m)
{
    const MembraneMaterial& r = m.rubber;
    for (const auto& [key, value] : {std::pair<const char*, double>{"youngs", r.youngs},
                                     {"thickness", r.thickness},
                                     {"density", r.density},
                                     {"radius", m.radius},
                                     {"height", m.height}})
        if (auto p = positiveProblem(key, value)) {
            if (std::string(key) == "density")
                p->fix = "a rubber's is about 1e-9 tonne/mm³; a larger one is mass scaling "
                         "(docs/dynamics.md#membrane)";
            return p;
        }
    if (!(r.poisson >= 0.0 && r.poisson < 0.5))
        return KeyProblem{"poisson", "must be in [0, 0.5) (got " + numberText(r.poisson) + ")",
                          "rubber is about 0.45-0.49"};
    if (auto p = nonNegativeProblem("pressure", m.pressure)) return p;
    if (auto p = nonNegativeProblem("drag", m.drag)) return p;
    if (auto p = nonFiniteProblem("base", m.base)) return p;
    if (auto p = nonFiniteProblem("axis", m.axis)) return p;
    if (!(m.axis.norm() > 0.0))
        return KeyProblem{"axis", "must not be zero", "give the tube's direction, e.g. [0, 0, 1]"};
    if (m.segments < 3)
        return KeyProblem{"segments", "must be at least 3 (got " + std::to_string(m.segments) + ")",
                          "about 2π·radius over the triangles' size"};
    if (m.rings < 1)
        return KeyProblem{"rings", "must be at least 1 (got " + std::to_string(m.rings) + ")",
                          "about height over the triangles' size"};
    // (A bound on what a few bytes can ask for: ten million vertices is over a gigabyte.)
    if (double(m.segments) * double(m.rings + 1) > 1e7)
        return KeyProblem{"segments", "and rings make " +
                                          numberText(double(m.segments) * double(m.rings + 1)) +
                                          " vertices, over the limit of 1e7",
                          "use triangles about a third of a grain across"};
    if (!(m.prestretch >= 1.0 && std::isfinite(m.prestretch)))
        return KeyProblem{"prestretch", "must be at least 1 (got " + numberText(m.prestretch) + ")",
                          "1 puts it on unstretched, 1.05 stretched 5 % round"};
    return std::nullopt;
}

Membrane makeMembrane(const MembraneSpec& spec, const std::vector<BoundarySpec>& boundaries)
{
    if (std::optional<KeyProblem> p = membraneProblem(spec))
        throw Error(spec.where, "membrane '" + spec.name + "': " + keyProblemText(*p), p->fix);
    Membrane m = makeTubeMembrane(spec.base, spec.axis.normalized(), spec.radius, spec.height,
                                  spec.segments, spec.rings, spec.rubber, spec.prestretch);
    if (!spec.state.empty()) readMembraneStateCsv(spec.state, m);  // placed as a run left it
    m.name = spec.name;
    m.material = spec.material;
    m.pressure = spec.pressure;
    m.drag = spec.drag;
    if (spec.hold.empty()) return m;

    // Each rim by the nearest of the holding planes.
    const std::vector<Vec3> centroid = rimCentroids(m);
    std::vector<int> holder(size_t(m.rimCount), -1);
    std::vector<char> holds(spec.hold.size(), 0);
    for (size_t r = 0; r < holder.size(); ++r) {
        const Vec3& c = centroid[r];
        double nearest = std::numeric_limits<double>::infinity();
        for (size_t k = 0; k < spec.hold.size(); ++k) {
            const BoundarySpec& b = boundaries.at(size_t(spec.hold[k]));
            if (b.shape != BoundaryShape::Plane)
                throw Error(spec.where, "membrane '" + spec.name + "' hold: '" + b.name +
                                            "' is not a plane",
                            "a membrane's rims are sealed to plane boundaries (platens)");
            const double distance = std::abs((c - b.point).dot(b.normal.normalized()));
            if (distance < nearest) nearest = distance, holder[r] = int(k);
        }
        holds[size_t(holder[r])] = 1;
    }
    for (size_t k = 0; k < spec.hold.size(); ++k)
        if (!holds[k])
            throw Error(spec.where, "membrane '" + spec.name + "' hold: '" +
                                        boundaries.at(size_t(spec.hold[k])).name +
                                        "' is the nearest boundary to none of its rims",
                        "name one plane per rim, each near the rim it holds");
    for (size_t e = 0; e < m.rimEdges.size(); ++e)
        for (int v : m.rimEdges[e])
            m.heldBy[size_t(v)] = spec.hold[size_t(holder[size_t(m.rimOfEdge[e])])];
    return m;
}

} // namespace lsdem

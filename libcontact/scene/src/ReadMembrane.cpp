// [[membranes]]: a flexible membrane round the grains (a triaxial sample's), for now a tube.
#include "SceneSections.h"

#include "lsdem/scene/MembraneKeys.h"

#include <algorithm>

namespace lsdem::scenefile {

namespace {

/// A count of vertices or rings, at most ten million (membraneProblem bounds their product).
int count(TableReader& t, const char* key)
{
    const long long n = t.integer(key);
    if (n > 10000000)
        t.fail(key, "must be at most 1e7 (got " + std::to_string(n) + ")",
               "use triangles about a third of a grain across");
    return int(n);
}

} // namespace

MembraneSpec readMembrane(TableReader& t, const Scene& scene)
{
    MembraneSpec m;
    m.where = t.where();
    m.name = t.string("name");
    m.material = lookUpMaterial(t, scene);
    const std::string shape = t.string("shape");
    if (shape != "tube")
        t.fail("shape", "unknown membrane shape '" + shape + "'",
               "use shape = \"tube\" (the only one so far)");
    m.rubber.youngs = t.number("youngs");
    m.rubber.poisson = t.number("poisson");
    m.rubber.thickness = t.number("thickness");
    m.rubber.density = t.number("density");
    m.pressure = t.number("pressure", 0.0);
    m.drag = t.number("drag", 0.0);
    m.base = t.vec3("base");
    m.axis = t.has("axis") ? t.vec3("axis") : Vec3::UnitZ();
    m.radius = t.number("radius");
    m.height = t.number("height");
    m.segments = count(t, "segments");
    m.rings = count(t, "rings");
    m.prestretch = t.number("prestretch", 1.0);
    if (t.has("hold")) {
        const toml::array* a = t.node("hold").as_array();
        if (!a || !std::all_of(a->begin(), a->end(), [](const toml::node& e) { return e.is_string(); }))
            t.fail("hold", "expected the names of the plane boundaries holding its rims",
                   "write e.g. hold = [\"bottom\", \"top\"]");
        for (const toml::node& e : *a) {
            const std::string name = e.as_string()->get();
            const int i = indexByName(scene.boundaries, name);
            if (i < 0)
                t.fail("hold", "no boundary named '" + name + "'",
                       "name one of the scene's [[boundaries]]");
            m.hold.push_back(i);
        }
    }
    if (t.has("state")) m.state = resolveScenePath(scene.directory, t.string("state"));
    t.rejectUnknownKeys();
    if (std::optional<KeyProblem> p = membraneProblem(m)) t.fail(p->key, p->problem, p->fix);
    return m;
}

} // namespace lsdem::scenefile

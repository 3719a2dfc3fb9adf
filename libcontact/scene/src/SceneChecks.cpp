// Checks across the sections of a scene: contact laws for every pair of materials that can
// meet, and distinct names.
#include "SceneChecks.h"

#include "lsdem/core/Error.h"

#include <algorithm>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace lsdem::scenefile {

/// Every pair of materials that can meet needs a [[contacts]] entry, and only one. The laws are
/// kept by pair and each material with grains is checked once: a table of every pair, or a
/// check per grain, would grow with the square of the file.
void checkContactPairs(const Scene& scene)
{
    std::map<std::pair<int, int>, const ContactSpec*> laws;
    for (const ContactSpec& c : scene.contacts) {
        const auto [it, fresh] = laws.emplace(std::minmax(c.materialA, c.materialB), &c);
        if (!fresh)
            throw Error(c.where,
                        "[[contacts]]: a second entry for materials '" +
                            scene.materials[static_cast<size_t>(c.materialA)].name + "' and '" +
                            scene.materials[static_cast<size_t>(c.materialB)].name + "'",
                        "the first is at " + it->second->where + "; keep one");
    }
    const size_t m = scene.materials.size();
    std::vector<int> grainsOf(m, 0);
    for (const GrainSpec& g : scene.grains) ++grainsOf[static_cast<size_t>(g.material)];
    std::vector<int> grainMaterials;  // in index order, so the first missing law is reported
    for (size_t i = 0; i < m; ++i)
        if (grainsOf[i] > 0) grainMaterials.push_back(static_cast<int>(i));
    auto require = [&](int a, int b, const std::string& where) {
        if (laws.count(std::minmax(a, b))) return;
        const std::string na = scene.materials[static_cast<size_t>(a)].name;
        const std::string nb = scene.materials[static_cast<size_t>(b)].name;
        throw Error(where, "no contact law between materials '" + na + "' and '" + nb + "'",
                    "add [[contacts]] with materials = [\"" + na + "\", \"" + nb +
                        "\"] and its normal_stiffness (from Python: scene.add_contact(\"" + na +
                        "\", \"" + nb + "\", normal_stiffness=...))");
    };
    std::vector<char> checked(m, 0);
    for (const GrainSpec& g : scene.grains) {
        // What a grain must meet depends only on its material: the first grain speaks for all.
        if (checked[static_cast<size_t>(g.material)]) continue;
        checked[static_cast<size_t>(g.material)] = 1;
        for (int other : grainMaterials)
            if (other != g.material || grainsOf[static_cast<size_t>(other)] >= 2)
                require(g.material, other, g.where);
        for (const BoundarySpec& b : scene.boundaries) require(g.material, b.material, b.where);
        for (const MembraneSpec& b : scene.membranes) require(g.material, b.material, b.where);
    }
}

void checkUniqueNames(const Scene& scene)
{
    // Unnamed grains are named by their index (defaultGrainName) when the world is built, so
    // those names count too: "grain1" and the unnamed grain 1 would be two rows of grains.csv.
    std::unordered_map<std::string, size_t> grainIndex;
    grainIndex.reserve(scene.grains.size());
    for (size_t i = 0; i < scene.grains.size(); ++i) {
        const GrainSpec& g = scene.grains[i];
        const std::string name = g.name.empty() ? defaultGrainName(i) : g.name;
        const auto [it, fresh] = grainIndex.emplace(name, i);
        if (fresh) continue;
        const GrainSpec& first = scene.grains[it->second];
        if (g.name.empty())
            throw Error(g.where,
                        "this grain has no name, so it is called '" + name +
                            "' by default, the name of the grain at " + first.where,
                        "rename the grain at " + first.where + ", or give this one a name");
        if (first.name.empty())
            throw Error(g.where,
                        "a grain named '" + name + "', the name the unnamed grain at " +
                            first.where + " gets by default",
                        "rename this grain, or give the one at " + first.where + " a name");
        throw Error(g.where, "a second grain named '" + name + "'",
                    "the first is at " + first.where + "; give grains distinct names");
    }
    std::map<std::string, const std::string*> seen;
    for (const BoundarySpec& b : scene.boundaries) {
        const auto [it, fresh] = seen.emplace(b.name, &b.where);
        if (!fresh)
            throw Error(b.where, "a second boundary named '" + b.name + "'",
                        "the first is at " + *it->second + "; give boundaries distinct names");
    }
    seen.clear();  // (a membrane's name names its history file, membrane_NAME.csv)
    for (const MembraneSpec& m : scene.membranes) {
        const auto [it, fresh] = seen.emplace(m.name, &m.where);
        if (!fresh)
            throw Error(m.where, "a second membrane named '" + m.name + "'",
                        "the first is at " + *it->second + "; give membranes distinct names");
    }
}

} // namespace lsdem::scenefile

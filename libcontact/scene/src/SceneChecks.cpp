// Checks across the sections of a scene: contact laws for every pair of materials that can
// meet, and distinct names.
#include "SceneSections.h"

#include <map>

namespace lsdem::scenefile {

/// Every pair of materials that can meet needs a [[contacts]] entry, and only one.
void checkContactPairs(const Scene& scene)
{
    const size_t m = scene.materials.size();
    std::vector<const ContactSpec*> table(m * m, nullptr);
    for (const ContactSpec& c : scene.contacts) {
        const size_t ab = static_cast<size_t>(c.materialA) * m + static_cast<size_t>(c.materialB);
        const size_t ba = static_cast<size_t>(c.materialB) * m + static_cast<size_t>(c.materialA);
        if (table[ab])
            throw Error(c.where,
                        "[[contacts]]: a second entry for materials '" +
                            scene.materials[static_cast<size_t>(c.materialA)].name + "' and '" +
                            scene.materials[static_cast<size_t>(c.materialB)].name + "'",
                        "the first is at " + table[ab]->where + "; keep one");
        table[ab] = table[ba] = &c;
    }
    std::vector<int> grainsOf(m, 0);
    for (const GrainSpec& g : scene.grains) ++grainsOf[static_cast<size_t>(g.material)];
    auto require = [&](int a, int b, const std::string& where) {
        if (table[static_cast<size_t>(a) * m + static_cast<size_t>(b)]) return;
        const std::string na = scene.materials[static_cast<size_t>(a)].name;
        const std::string nb = scene.materials[static_cast<size_t>(b)].name;
        throw Error(where, "no contact law between materials '" + na + "' and '" + nb + "'",
                    "add [[contacts]] with materials = [\"" + na + "\", \"" + nb +
                        "\"] and its normal_stiffness");
    };
    for (const GrainSpec& g : scene.grains) {
        for (size_t other = 0; other < m; ++other) {
            const bool meets = static_cast<int>(other) == g.material ? grainsOf[other] >= 2
                                                                     : grainsOf[other] >= 1;
            if (meets) require(g.material, static_cast<int>(other), g.where);
        }
        for (const BoundarySpec& b : scene.boundaries) require(g.material, b.material, b.where);
    }
}

void checkUniqueNames(const Scene& scene)
{
    std::map<std::string, const std::string*> seen;
    for (const GrainSpec& g : scene.grains) {
        if (g.name.empty()) continue;
        const auto [it, fresh] = seen.emplace(g.name, &g.where);
        if (!fresh)
            throw Error(g.where, "a second grain named '" + g.name + "'",
                        "the first is at " + *it->second + "; give grains distinct names");
    }
    seen.clear();
    for (const BoundarySpec& b : scene.boundaries) {
        const auto [it, fresh] = seen.emplace(b.name, &b.where);
        if (!fresh)
            throw Error(b.where, "a second boundary named '" + b.name + "'",
                        "the first is at " + *it->second + "; give boundaries distinct names");
    }
}

} // namespace lsdem::scenefile

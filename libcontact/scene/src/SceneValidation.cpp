// The rules of a whole scene (SceneValidation.h), section by section, then across sections
// (SceneChecks.h: names, contact laws per pair of materials).
#include "lsdem/scene/SceneValidation.h"

#include "SceneChecks.h"

#include "lsdem/scene/BoundaryKeys.h"
#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/GrainKeys.h"
#include "lsdem/scene/MembraneKeys.h"
#include "lsdem/scene/SceneSettings.h"

#include "lsdem/contact/ContactCoefficients.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <cmath>
#include <string>

namespace lsdem {

namespace {

/// @a index names one of @a count entries.
bool inRange(int index, size_t count)
{
    return index >= 0 && static_cast<size_t>(index) < count;
}

/// "where: what" of an entry, for the few built in code without a `where`.
std::string placeOf(const std::string& where, const std::string& fallback)
{
    return where.empty() ? fallback : where;
}

void validateMaterials(const Scene& s)
{
    for (const MaterialSpec& m : s.materials) {
        if (m.name.empty()) throw Error(s.path, "a material without a name", "give it a name");
        if (std::optional<std::string> p = densityProblem(m.density))
            throw Error(s.path, "material '" + m.name + "': density " + *p, kDensityFix);
    }
}

void validateContacts(const Scene& s)
{
    for (const ContactSpec& c : s.contacts) {
        const std::string where = placeOf(c.where, s.path);
        if (!inRange(c.materialA, s.materials.size()) || !inRange(c.materialB, s.materials.size()))
            throw Error(where, "[[contacts]]: a material index out of range",
                        "name two materials of the scene");
        if (const std::optional<ContactProblem> p = checkContactModel(c.model))
            throw Error(where, "[[contacts]] " + p->key + ": " + p->problem, p->fix);
    }
}

void validateGrains(const Scene& s)
{
    for (size_t i = 0; i < s.grains.size(); ++i) {
        const GrainSpec& g = s.grains[i];
        const std::string where = placeOf(g.where, "grain " + std::to_string(i));
        if (!inRange(g.asset, s.assets.size()))
            throw Error(where, "the grain's asset index is out of range", "name an asset");
        if (!inRange(g.material, s.materials.size()))
            throw Error(where, "the grain's material index is out of range", "name a material");
        // The rules a file's entry obeys, applied to the keys that would write this grain.
        GrainSpec checked;
        if (std::optional<KeyProblem> p = applyGrainKeys(grainKeysOf(g), checked))
            throw Error(where, "the grain's " + keyProblemText(*p), p->fix);
    }
}

void validateBoundaries(const Scene& s)
{
    for (size_t i = 0; i < s.boundaries.size(); ++i) {
        const BoundarySpec& b = s.boundaries[i];
        const std::string where = placeOf(b.where, "boundary " + std::to_string(i));
        if (b.name.empty()) throw Error(where, "a boundary without a name", "give it a name");
        if (!inRange(b.material, s.materials.size()))
            throw Error(where, "boundary '" + b.name + "': its material index is out of range",
                        "name a material");
        if (b.shape == BoundaryShape::LevelSet && !inRange(b.asset, s.assets.size()))
            throw Error(where, "boundary '" + b.name + "': its asset index is out of range",
                        "name an asset");
        // The rules a file's entry obeys, applied to the keys that would write this boundary.
        BoundarySpec checked;
        if (std::optional<KeyProblem> p = applyBoundaryKeys(boundaryKeysOf(b, s), checked))
            throw Error(where, "boundary '" + b.name + "': " +
                                   keyProblemText(*p),
                        p->fix);
    }
}

void validateMembranes(const Scene& s)
{
    for (size_t i = 0; i < s.membranes.size(); ++i) {
        const MembraneSpec& m = s.membranes[i];
        const std::string where = placeOf(m.where, "membrane " + std::to_string(i));
        if (m.name.empty()) throw Error(where, "a membrane without a name", "give it a name");
        if (!inRange(m.material, s.materials.size()))
            throw Error(where, "membrane '" + m.name + "': its material index is out of range",
                        "name a material");
        for (int b : m.hold)
            if (!inRange(b, s.boundaries.size()))
                throw Error(where, "membrane '" + m.name + "': a holding boundary's index is "
                                   "out of range", "name the scene's plane boundaries");
        if (std::optional<KeyProblem> p = membraneProblem(m))
            throw Error(where, "membrane '" + m.name + "': " + keyProblemText(*p), p->fix);
    }
}

/// "[simulation]", or "scene.toml: [simulation]" for a scene read from a file.
std::string sectionPlace(const Scene& s, const std::string& section)
{
    return s.path.empty() ? "[" + section + "]" : s.path + ": [" + section + "]";
}

/// [simulation] and [output]: each setting in its range (SceneSettings.h), then the rules
/// between them.
void validateSettings(const Scene& s)
{
    for (const SceneSetting& setting : sceneSettings())
        checkSetting(setting, setting.get(s), sectionPlace(s, setting.section));
    const EndCondition& e = s.end;
    if (e.boundary >= 0 && (!inRange(e.boundary, s.boundaries.size()) ||
                            !(std::isfinite(e.displacement) && e.displacement > 0.0)))
        throw Error(sectionPlace(s, "simulation"),
                    "end_displacement needs a boundary of the scene and a value > 0", "");
    if (s.output.historyEvery > 0 && s.output.historyPeriod > 0.0)
        throw Error(sectionPlace(s, "output"), "both history_every and history_period are given",
                    "keep one (set the other to 0)");
}

} // namespace

void validateRunnableScene(const Scene& scene)
{
    validateScene(scene);
    const EndCondition& e = scene.end;
    if (e.time <= 0.0 && e.steps <= 0 && e.boundary < 0)
        throw Error(sectionPlace(scene, "simulation"), "has no end condition", "add end_time, end_steps or end_displacement");
}

void validateScene(const Scene& scene)
{
    validateMaterials(scene);
    validateContacts(scene);
    validateGrains(scene);
    validateBoundaries(scene);
    validateMembranes(scene);
    validateSettings(scene);
    scenefile::checkUniqueNames(scene);
    scenefile::checkContactPairs(scene);
}

} // namespace lsdem

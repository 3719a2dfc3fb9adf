// [[contacts]]: the contact law between two materials.
#include "SceneSections.h"

#include "lsdem/contact/ContactCoefficients.h"

namespace lsdem::scenefile {

ContactSpec readContact(TableReader& t, const Scene& scene)
{
    ContactSpec c;
    c.where = t.where();
    const toml::node& m = t.node("materials");
    const toml::array* pair = m.as_array();
    if (!pair || pair->size() != 2 || !(*pair)[0].is_string() || !(*pair)[1].is_string())
        t.fail("materials", "expected two material names", "write materials = [\"steel\", \"wall\"]");
    int idx[2];
    for (int s = 0; s < 2; ++s) {
        const std::string name = (*pair)[static_cast<size_t>(s)].as_string()->get();
        idx[s] = indexByName(scene.materials, name);
        if (idx[s] < 0)
            t.fail("materials", "no material named '" + name + "'", "define [materials." + name + "]");
    }
    c.materialA = idx[0];
    c.materialB = idx[1];
    ContactModel& model = c.model;
    // The words and the numbers, as the contact library's schema lists them
    // (ContactCoefficients.h).
    for (const ContactChoice& k : contactChoices())
        k.set(model, t.choice(k.key, k.values, k.defaultValue()));
    for (const ContactCoefficient& k : contactCoefficients()) {
        const double v = k.defaultValue ? t.number(k.key, *k.defaultValue) : t.number(k.key);
        if (std::optional<ContactProblem> p = k.rangeProblem(v)) t.fail(p->key, p->problem, p->fix);
        k.set(model, v);
    }
    if (std::optional<ContactProblem> p = checkContactModel(model))
        t.fail(p->key, p->problem, p->fix);
    t.rejectUnknownKeys();
    return c;
}

} // namespace lsdem::scenefile

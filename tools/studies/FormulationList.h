/// @file FormulationList.h
/// @brief The check every study makes of its --formulation list.
#pragma once

#include "lsdem/contact/ContactModel.h"
#include "lsdem/core/Error.h"

#include <algorithm>
#include <vector>

namespace lsdem {

/// Throw Error unless @a formulations is non-empty and names each formulation once (a repeat
/// would be run once but counted twice, and compare the finest run with itself).
inline void checkFormulationList(const std::vector<Formulation>& formulations)
{
    if (formulations.empty()) throw Error("", "--formulation needs at least one formulation");
    for (size_t i = 0; i < formulations.size(); ++i)
        if (std::find(formulations.begin(), formulations.begin() + i, formulations[i]) !=
            formulations.begin() + i)
            throw Error("", "--formulation lists " + formulationName(formulations[i]) + " twice",
                        "name each formulation once");
}

} // namespace lsdem

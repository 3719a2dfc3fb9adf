// The normal sub-models, one per file (NormalModel<Name>.cpp); NormalModel.cpp registers them
// (its registry(): one line each) and hands them out by formulation.
#pragma once

#include "lsdem/contact/NormalModel.h"

namespace lsdem::normal_models {

const NormalModel& original();
const NormalModel& adapted();
const NormalModel& singleNode();
const NormalModel& volume();

} // namespace lsdem::normal_models

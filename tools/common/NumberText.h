/// @file NumberText.h
/// @brief Numbers in the programs' messages: lsdem::numberText (the shortest text that reads
///        back to the same double), under the name the tools use.
#pragma once

#include "lsdem/ls/NumberText.h"

namespace lsdem::cli {

using lsdem::numberText;

} // namespace lsdem::cli

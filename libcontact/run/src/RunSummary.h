// The summary a run prints at its end (private to the run library): where the time went and
// the throughput.
#pragma once

#include "lsdem/run/SimulationRun.h"

#include <iosfwd>

namespace lsdem {

void printRunSummary(std::ostream& log, const RunResult& r);

} // namespace lsdem

// The end check of a run, shared by lsdem-run and the Python module.
#include "lsdem/run/RunEnd.h"

namespace lsdem {

bool endReached(const Scene& scene, const World& w, double dt)
{
    const EndCondition& end = scene.end;
    if (end.steps > 0 && w.step >= end.steps) return true;
    if (end.time > 0.0 && w.time >= end.time - 1e-9 * dt) return true;
    if (end.boundary >= 0 && w.boundaries[end.boundary].displacement.norm() >= end.displacement)
        return true;
    return false;
}

} // namespace lsdem

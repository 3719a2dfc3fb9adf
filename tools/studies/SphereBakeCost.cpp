#include "studies/SphereBakeCost.h"

#include <cmath>

namespace lsdem {

double sphereBakeSeconds(double radius, double voxel, int nodes)
{
    // Fitted to lsdem-bake --sphere on this machine (idle, 2 cores, 2026-11-29), R 0.5 to 5 mm,
    // voxel 0.025 to 0.1 mm, 200 to 16,000 nodes: the level set takes about 60 ns per voxel
    // of the ball's bounding box (R/voxel = 50 to 200), the remesher about 1.05e-4 s × N^1.1
    // (a little more than linear: a finer surface takes more of its passes).
    const double voxelsAcross = 2.0 * radius / voxel;
    const double levelSet = 6.0e-8 * voxelsAcross * voxelsAcross * voxelsAcross;
    const double remesh = 1.05e-4 * std::pow(double(nodes > 0 ? nodes : 0), 1.1);
    return levelSet + remesh;
}

} // namespace lsdem

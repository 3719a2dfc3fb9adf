#include "studies/SlabFailure.h"

#include "lsdem/core/NumberText.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace lsdem {

namespace {

/// How far the blocks around the centre moved at the end of a run.
struct BlockMotion
{
    double neighbours = 0, diagonal = 0, rest = 0;  ///< largest displacement per ring, mm
    int farMoved = 0;                               ///< other blocks moved more than t/3
    std::string farNames;
};

BlockMotion blockMotion(const SlabPanel& panel, const SlabRunResult& run)
{
    BlockMotion m;
    const int centre = panel.centralBlock();
    const std::vector<SlabBlock>& blocks = panel.blocks();
    for (int k = 0; k < static_cast<int>(blocks.size()); ++k) {
        if (k == centre) continue;
        const double d = run.finalDisplacement[k].norm();
        const int di = std::abs(blocks[k].i - blocks[centre].i), dj = std::abs(blocks[k].j - blocks[centre].j);
        double& ring = di + dj == 1 ? m.neighbours : std::max(di, dj) == 1 ? m.diagonal : m.rest;
        ring = std::max(ring, d);
        if (d > panel.options().thickness / 3) {
            ++m.farMoved;
            m.farNames += " " + blocks[k].name + " (" + roundedText(std::round(d * 100) / 100) + " mm)";
        }
    }
    return m;
}

/// Whether every block ended where a number says (a run that went unstable has NaN or inf).
bool hasFinitePositions(const SlabRunResult& run)
{
    return std::all_of(run.finalDisplacement.begin(), run.finalDisplacement.end(),
                       [](const Vec3& d) { return d.allFinite(); });
}

} // namespace

SlabFailureMode slabFailureMode(const SlabPanel& panel, const SlabRunResult& run)
{
    if (run.finalDisplacement.size() != panel.blocks().size() || run.curve.empty() ||
        !hasFinitePositions(run))
        return SlabFailureMode::None;
    const BlockMotion m = blockMotion(panel, run);
    const double drop = -run.finalDisplacement[panel.centralBlock()].z();
    const double delta = run.curve.back().delta;
    const double others = std::max({m.neighbours, m.diagonal, m.rest});
    if (drop > 0.5 * delta && others < 0.25 * drop && m.farMoved == 0) return SlabFailureMode::PushOut;
    if (m.farMoved > 0) return SlabFailureMode::BlocksDisplaced;
    return SlabFailureMode::Deflection;
}

std::string slabFailureModeName(SlabFailureMode mode)
{
    switch (mode) {
    case SlabFailureMode::PushOut: return "push-out";
    case SlabFailureMode::BlocksDisplaced: return "blocks-displaced";
    case SlabFailureMode::Deflection: return "deflection";
    case SlabFailureMode::None: break;
    }
    return "none";
}

std::string slabFailureSummary(const SlabPanel& panel, const SlabRunResult& run)
{
    std::ostringstream s;
    s << std::fixed << std::setprecision(3);
    const int n = panel.n(), centre = panel.centralBlock();
    if (run.finalDisplacement.size() != panel.blocks().size()) return "no result\n";
    const double delta = run.curve.empty() ? 0.0 : run.curve.back().delta;
    const BlockMotion m = blockMotion(panel, run);
    const Vec3 c = run.finalDisplacement[centre];
    s << formulationName(run.formulation) << ", SDP " << run.sdp << " mm, VDP " << run.vdp
      << " mm (" << run.nodes << " nodes per block), at delta = " << delta << " mm:\n";
    if (run.stopped) s << "  the run stopped early: " << run.error << "\n";
    if (!hasFinitePositions(run)) {
        s << "  the blocks' positions are not finite numbers (the run went unstable): no "
             "failure mode to tell\n";
        return s.str();
    }
    s << "  central block " << panel.blocks()[centre].name << " moved down by " << -c.z()
      << " mm (sideways " << c.head<2>().norm() << " mm)\n"
      << "  its 4 face neighbours moved at most " << m.neighbours << " mm, the 4 diagonal ones "
      << m.diagonal << " mm";
    if (n > 3) s << ", the other " << n * n - 9 << " blocks " << m.rest << " mm";
    s << "\n";
    switch (slabFailureMode(panel, run)) {
    case SlabFailureMode::PushOut:
        s << "  => push-out of the central block; the rest of the panel stays largely intact\n";
        break;
    case SlabFailureMode::BlocksDisplaced:
        s << "  => " << m.farMoved << " other block(s) moved more than t/3 and stayed:"
          << m.farNames << "\n";
        break;
    default: s << "  => the panel deflects as a whole (no block pushed out)\n";
    }
    return s.str();
}

} // namespace lsdem

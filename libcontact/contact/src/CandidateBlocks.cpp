#include "lsdem/contact/CandidateBlocks.h"

namespace lsdem {

// The runs are built in this thread's buffer and copied back, so a pair allocates only when
// its runs outgrow what it holds.
void leaveOutNodes(std::vector<std::pair<int, int>>& runs, const std::vector<int>& nodes)
{
    thread_local std::vector<std::pair<int, int>> kept;
    kept.clear();
    size_t k = 0;
    for (auto [begin, end] : runs) {
        for (; k < nodes.size() && nodes[k] < end; ++k) {
            if (nodes[k] > begin) kept.emplace_back(begin, nodes[k]);
            begin = nodes[k] + 1;
        }
        if (begin < end) kept.emplace_back(begin, end);
    }
    runs.assign(kept.begin(), kept.end());
}

void leaveOutNodes(std::vector<CandidateBlocks::SampledCell>& cells, const std::vector<int>& nodes)
{
    size_t kept = 0, k = 0;
    for (const CandidateBlocks::SampledCell& c : cells) {
        while (k < nodes.size() && nodes[k] < c.node) ++k;
        if (k < nodes.size() && nodes[k] == c.node) continue;
        cells[kept++] = c;
    }
    cells.resize(kept);
}

} // namespace lsdem

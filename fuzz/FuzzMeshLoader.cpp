// Fuzz target for the mesh loader and what lsdem-bake does with a mesh: read the file through
// assimp (readMesh), validate it as a solid, move it to its principal frame and sample a coarse
// level set with the mesh's own vertices as nodes. Compiled once per format: the extension
// (LSDEM_FUZZ_MESH_EXTENSION) picks assimp's importer.
#include "FuzzSupport.h"

#include "lsdem/ls/Bake.h"
#include "lsdem/mesh/MeshIO.h"

#include <tbb/global_control.h>

#include <cmath>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    // One thread: the fuzzers share two cores, and a single thread keeps runs reproducible.
    static const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
    const std::string path = lsdem::fuzz::writeScratchFile(data, size, LSDEM_FUZZ_MESH_EXTENSION);
    try {
        lsdem::TriangleMesh mesh = lsdem::readMesh(path);
        // A dozen voxels along the longest side and a small memory budget keep each bake
        // quick; thinner shapes are refused by the bake's own checks, which is fine here.
        const auto bounds = lsdem::meshBounds(mesh);
        lsdem::BakeOptions options;
        options.voxelSize = (bounds[1] - bounds[0]).maxCoeff() / 12.0;
        // Non-finite or flat meshes: any valid voxel, so validation still has its say.
        if (!(options.voxelSize > 0.0 && std::isfinite(options.voxelSize)))
            options.voxelSize = 1.0;
        options.nodePlacement = lsdem::NodePlacement::MeshVertices;
        options.memoryBudgetBytes = 64.0 * 1024 * 1024;
        std::vector<std::string> warnings;
        lsdem::bakeMesh(std::move(mesh), path, options, warnings);
    } catch (const lsdem::Error& e) {
        lsdem::fuzz::requireClearError(e);
    }
    return 0;
}

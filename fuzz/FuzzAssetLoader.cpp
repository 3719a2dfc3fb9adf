// Fuzz target for the asset loader: any bytes in a .vdb file must load as an asset or give a
// clear lsdem::Error naming the file.
#include "FuzzSupport.h"

#include "lsdem/ls/AssetIO.h"

#include <tbb/global_control.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    // One thread: the fuzzers share two cores, and a single thread keeps runs reproducible.
    static const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
    const std::string path = lsdem::fuzz::writeScratchFile(data, size, ".vdb");
    try {
        lsdem::loadAsset(path);
    } catch (const lsdem::Error& e) {
        lsdem::fuzz::requireClearError(e);
    }
    return 0;
}

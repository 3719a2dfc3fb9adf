// Fuzz target for the scene reader: any text must give a Scene or a clear lsdem::Error.
// The scene's path is in assets/scenes/ so that the bundled examples' relative asset paths
// (../meshes/pebble.obj) resolve and the fuzzer gets past the [assets] tables.
#include "FuzzSupport.h"

#include "lsdem/scene/SceneFile.h"

#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        lsdem::parseScene(text, LSDEM_SOURCE_DIR "/assets/scenes/fuzz-input.toml");
    } catch (const lsdem::Error& e) {
        lsdem::fuzz::requireClearError(e);
    }
    return 0;
}

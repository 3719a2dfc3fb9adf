/// @file SlicePlot.h
/// @brief Draw φ on an axis-aligned plane as a PNG: a diverging colour map (blue inside, red
///        outside), the zero contour in black, and the surface nodes near the plane as dots.
#pragma once

#include "lsdem/ls/Inspection.h"

#include <string>

namespace lsdem {

struct SliceSpec
{
    int axis = 2;          ///< 0, 1, 2 for a plane of constant x, y, z
    double value = 0.0;    ///< the plane's coordinate, in the asset frame
    int maxPixels = 800;   ///< longest side of the image
};

/// Parse "z=0", "x=-1.5", ... @throw Error for anything else.
SliceSpec parseSliceSpec(const std::string& text);

/// Render the slice of @a target to @a pngPath (written atomically).
/// @throw Error if the plane misses the grid or the file cannot be written.
void writeSlicePng(const InspectionTarget& target, const SliceSpec& slice,
                   const std::string& pngPath);

} // namespace lsdem

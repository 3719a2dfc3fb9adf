/// @file BoundaryKeys.h
/// @brief The schema of a [[boundaries]] entry (docs/scenes.md), written once for every front
///        end: which keys each type of boundary takes, which it needs, and the rules of their
///        values. The scene reader gathers what an entry gives, Python's add_plane,
///        add_sphere_boundary, ... what their arguments give, validateScene what a Scene built
///        in code holds (boundaryKeysOf), and all three ask applyBoundaryKeys, which names the
///        key at fault in the same words. The scene writer writes boundaryKeysOf, so what it
///        writes is what the reader reads back.
#pragma once

#include "lsdem/scene/Scene.h"
#include "lsdem/scene/ServoKeys.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace lsdem {

/// What a [[boundaries]] entry gives, key by key, before any rule is applied (a key not given:
/// std::nullopt). The material and asset come as indices: each front end looks their names up
/// in its own way (a file lists the names it knows, Python the same).
struct BoundaryKeys
{
    std::string name;
    std::string type;  ///< "plane", "sphere", "level-set", "cylinder" or "orifice"; "" if absent
    int material = -1;
    std::optional<Vec3> velocity;
    // A plane: a point of it, its normal and optionally a finite patch.
    std::optional<Vec3> point, normal;
    std::optional<std::array<double, 2>> extent;
    std::optional<Vec3> axisU;
    std::optional<double> thickness;  ///< also an orifice plate's
    // A sphere, cylinder or orifice.
    std::optional<Vec3> center;
    std::optional<double> radius;
    std::optional<Vec3> axis;
    // A level-set obstacle.
    std::optional<int> asset;
    std::optional<Vec3> position;
    std::optional<Quat> orientation;
    /// A plane's stress servo (its velocityGiven is ignored: velocity above says it).
    ServoKeys servo;
};

/// One type of boundary: its name in a file, its shape, the keys it needs and those it may
/// have besides the common ones (name, type, material, velocity), and where grains live.
struct BoundaryType
{
    std::string name;
    BoundaryShape shape;
    std::vector<std::string> required;
    std::vector<std::string> optional;
    std::string grainsLive;  ///< "outside it", ...
};

/// Every type of boundary, in the order docs/scenes.md lists them.
const std::vector<BoundaryType>& boundaryTypes();

/// The type called @a name, or null.
const BoundaryType* boundaryType(const std::string& name);

/// The type of @a shape.
const BoundaryType& boundaryTypeOf(BoundaryShape shape);

/// The first rule @a keys break, in the order a reader meets them: a known type, only keys that
/// type takes, the keys it needs, their values (sizes > 0, directions not zero, a patch's axis
/// within the plane), then the servo's rules (ServoKeys.h). If none, @a out is the boundary
/// (directions made unit) and nothing is returned; otherwise @a out is left as it was.
std::optional<KeyProblem> applyBoundaryKeys(const BoundaryKeys& keys, BoundarySpec& out);

/// The keys that give @a b: those its type needs, and the others where they differ from their
/// defaults (a fixed boundary has no velocity). A servo's area walls are named by the walls'
/// names in @a scene. What the scene writer writes, and what validateScene checks.
BoundaryKeys boundaryKeysOf(const BoundarySpec& b, const Scene& scene);

} // namespace lsdem

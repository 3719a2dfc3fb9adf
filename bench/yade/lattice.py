"""The geometry of the YADE comparison, shared by compare.py (lsdem's scene) and
yade_lattice.py (YADE's): 1000 level-set spheres in a 10 x 10 x 10 lattice inside five walls
(no lid), each overlapping its neighbours and the walls by `overlap` (0: touching).
Units: mm, tonne, s, N. Plain Python: YADE's interpreter imports it too."""

RADIUS = 1.0
COUNT = 10              # spheres along each axis
GRID_SPACING = 0.1      # the level set's voxel
NODES = 1000            # surface nodes a sphere
NORMAL_STIFFNESS = 1e3  # N/mm: kn for single-node (and YADE), kn* N/mm^3 for adapted
DENSITY = 2.65e-9       # tonne/mm^3
GRAVITY = -9810.0       # mm/s^2, along z
TIME_STEP = 1e-7        # s


def spacing(overlap):
    """The distance between neighbouring centres."""
    return 2.0 * RADIUS - overlap


def centres(overlap):
    """Every sphere's centre, z slowest and x fastest (the order of lsdem's [[lattices]])."""
    s = spacing(overlap)
    return [(i * s, j * s, RADIUS + k * s) for k in range(COUNT) for j in range(COUNT) for i in range(COUNT)]


def planes(overlap):
    """The five walls as (name, point, outward normal into the box), from walls()."""
    w = walls(overlap)
    return [("floor", (0.0, 0.0, w["floor"]), (0, 0, 1)),
            ("west", (w["low"], 0.0, 0.0), (1, 0, 0)),
            ("east", (w["high"], 0.0, 0.0), (-1, 0, 0)),
            ("south", (0.0, w["low"], 0.0), (0, 1, 0)),
            ("north", (0.0, w["high"], 0.0), (0, -1, 0))]


def walls(overlap):
    """The floor's height and the side walls' lower and upper coordinates (x and y alike)."""
    low = -RADIUS + overlap
    high = (COUNT - 1) * spacing(overlap) + RADIUS - overlap
    return {"floor": overlap, "low": low, "high": high}

# YADE's level-set DEM on the scene bench/yade/compare.py gives lsdem-run: 1000 level-set spheres
# (radius 1, grid spacing 0.1, 1000 surface nodes) in a 10 x 10 x 10 lattice inside five walls,
# under gravity, each sphere touching its neighbours and the walls, or overlapping them by
# OVERLAP; times O.run(steps) alone (the bodies' making and the first step are left out).
# Run: yade -j1 -n -x bench/yade/yade_lattice.py [STEPS [OVERLAP]]   (units: mm, tonne, s, N)
import sys, time
steps = int(sys.argv[1]) if len(sys.argv) > 1 else 200
overlap = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0
radius, count = 1.0, 10
spacing = 2 * radius - overlap

O.materials.append(FrictMat(density=2.65e-9, frictionAngle=0.0, label='grain'))
O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_LevelSet_Aabb(), Bo1_Wall_Aabb()], verletDist=0),
        InteractionLoop([Ig2_LevelSet_LevelSet_ScGeom(), Ig2_Wall_LevelSet_ScGeom()],
                        [Ip2_FrictMat_FrictMat_FrictPhys(kn=MatchMaker(algo='val', val=1.0e3),
                                                         ks=MatchMaker(algo='val', val=0.0))],
                        [Law2_ScGeom_FrictPhys_CundallStrack(sphericalBodies=False)]),
        NewtonIntegrator(damping=0.0, gravity=(0, 0, -9810.0)),
]
# One grid and distance field for all (as lsdem shares one baked asset between its grains).
first = levelSetBody('sphere', center=(0, 0, 0), radius=radius, spacing=0.1, nSurfNodes=1000,
                     nodesPath=2)
grid, field = first.shape.lsGrid, first.shape.distField
for i in range(count):
    for j in range(count):
        for k in range(count):
            O.bodies.append(levelSetBody(center=(i * spacing, j * spacing, radius + k * spacing),
                                         grid=grid, distField=field, nSurfNodes=1000,
                                         nodesPath=2, material='grain'))
low, high = -radius + overlap, (count - 1) * spacing + radius - overlap
O.bodies.append(wall((0, 0, overlap), 2))
O.bodies.append(wall((low, 0, 0), 0))
O.bodies.append(wall((high, 0, 0), 0))
O.bodies.append(wall((0, low, 0), 1))
O.bodies.append(wall((0, high, 0), 1))
O.dt = 1.0e-7
O.run(1, True)  # the first step builds the collider's lists: not timed
start = time.time()
O.run(steps, True)
elapsed = time.time() - start
print('yade: %d bodies, %d surface nodes each, %d steps in %.3f s: %.2f ms/step, %d interactions'
      % (len(O.bodies) - 5, len(first.shape.surfNodes), steps, elapsed, 1e3 * elapsed / steps,
         len([i for i in O.interactions if i.isReal])))

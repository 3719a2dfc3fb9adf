# YADE's level-set DEM on the scene compare.py gives lsdem-run (geometry: lattice.py): 1000
# level-set spheres (radius 1, grid spacing 0.1, 1000 surface nodes) in a 10 x 10 x 10 lattice
# inside five walls, under gravity, each sphere touching its neighbours and the walls, or
# overlapping them by OVERLAP; times O.run(steps) alone (the bodies' making and the first step
# are left out).
# Run: yade -j1 -n -x bench/yade/yade_lattice.py [STEPS [OVERLAP]]   (units: mm, tonne, s, N)
import os, sys, time
sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
import lattice

steps = int(sys.argv[1]) if len(sys.argv) > 1 else 200
overlap = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0

O.materials.append(FrictMat(density=lattice.DENSITY, frictionAngle=0.0, label='grain'))
O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_LevelSet_Aabb(), Bo1_Wall_Aabb()], verletDist=0),
        InteractionLoop([Ig2_LevelSet_LevelSet_ScGeom(), Ig2_Wall_LevelSet_ScGeom()],
                        [Ip2_FrictMat_FrictMat_FrictPhys(kn=MatchMaker(algo='val', val=lattice.NORMAL_STIFFNESS),
                                                         ks=MatchMaker(algo='val', val=0.0))],
                        [Law2_ScGeom_FrictPhys_CundallStrack(sphericalBodies=False)]),
        NewtonIntegrator(damping=0.0, gravity=(0, 0, lattice.GRAVITY)),
]
# One grid and distance field for all (as lsdem shares one baked asset between its grains).
first = levelSetBody('sphere', center=(0, 0, 0), radius=lattice.RADIUS, spacing=lattice.GRID_SPACING,
                     nSurfNodes=lattice.NODES, nodesPath=2)
grid, field = first.shape.lsGrid, first.shape.distField
for centre in lattice.centres(overlap):
    O.bodies.append(levelSetBody(center=centre, grid=grid, distField=field, nSurfNodes=lattice.NODES,
                                 nodesPath=2, material='grain'))
for _, point, normal in lattice.planes(overlap):
    O.bodies.append(wall(point, [abs(n) for n in normal].index(1)))  # a plane square to that axis
O.dt = lattice.TIME_STEP
O.run(1, True)  # the first step builds the collider's lists: not timed
start = time.time()
O.run(steps, True)
elapsed = time.time() - start
print('yade: %d bodies, %d surface nodes each, %d steps in %.3f s: %.2f ms/step, %d interactions'
      % (len(O.bodies) - 5, len(first.shape.surfNodes), steps, elapsed, 1e3 * elapsed / steps,
         len([i for i in O.interactions if i.isReal])))

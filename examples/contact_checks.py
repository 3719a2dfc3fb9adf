"""Single-contact checks by hand, through `import lsdem`: the figures of issue 33's table
(docs/verification.md, "What the suite found"). An oblique impact against rigid-body theory, a
ball thrown flat on a floor (slide, then roll), a box landing flat with the automatic time step
and at three restitutions, a ball's rebound at two. Prints each against its theory.

    PYTHONPATH=build/python /usr/bin/python3 examples/contact_checks.py    # about a minute

lsdem-study verify does all this and more, with references derived for each law; this script
shows how to set such a case up in a few lines of Python."""
import math, sys, tempfile, os
import numpy as np
import lsdem

R, RHO, G = 5.0, 7.85e-9, 9810.0
tmp = tempfile.mkdtemp()

def ball(nodes=4000, voxel=0.1):
    a = lsdem.bake_sphere(R, voxel=voxel, nodes=nodes)
    a.save(os.path.join(tmp, f"ball{nodes}.vdb"))
    return a

def block():
    a = lsdem.bake_box(10, 10, 4, voxel=0.1, node_spacing=0.25)
    a.save(os.path.join(tmp, "box.vdb"))
    return a

def scene(asset, pos, vel=(0, 0, 0), e=1.0, mu=0.0, ks=0.5e3, gravity=(0, 0, 0), dt=0.0,
          quadrature="node"):
    s = lsdem.Scene()
    s.add_asset("g", asset)
    s.add_material("steel", density=RHO); s.add_material("wall")
    kw = dict(formulation="adapted", normal_stiffness=1e3, restitution=e, quadrature=quadrature)
    if mu > 0: kw.update(shear_stiffness=ks, friction=mu)
    s.add_contact("steel", "wall", **kw)
    s.add_grain("g", "steel", list(pos), velocity=list(vel))
    s.add_plane("floor", "wall", point=[0, 0, 0], normal=[0, 0, 1])
    s.gravity = list(gravity); s.time_step = dt; s.end_steps = 10**9
    return s

def impact(s, half):
    sim = lsdem.Simulation(s, threads=2, record_contacts=False)
    touched = False
    while True:
        sim.run(steps=1)
        z = sim.grains.positions[0][2]
        if z < half: touched = True
        if touched and z > half + 0.002: break
    return sim

b = ball()
print("case | theory | lsdem")
# 1. oblique impact at 60° from the normal, mu 0.1, e 1.
V, th, mu = 3900.0, math.radians(60), 0.1
vt, vn = V * math.sin(th), V * math.cos(th)
sim = impact(scene(b, (0, 0, R + 0.005), (vt, 0, -vn), mu=mu, dt=2e-7), R)
v = sim.grains.velocities[0]; w = sim.grains.angular_velocities[0]
print(f"oblique 60°: v_t' {100*(v[0]/(vt - 2*mu*vn)-1):+.2f} %, omega' {100*(abs(w[1])/(5*mu*2*vn/(2*R))-1):+.2f} %")
# 2./3. slide-to-roll, mu 0.3, e 0.3 and 1, gravity; v0 1 m/s; the nodes as points (the
# paper's rule) and as patches (docs/contact.md, patch quadrature).
for quadrature, e in [(q, e) for q in ("node", "patch") for e in (0.3, 1.0)]:
    v0, mu = 1000.0, 0.3
    ts, vs = 2 * v0 / (7 * mu * G), 5 / 7 * v0
    s = scene(b, (0, 0, R), (v0, 0, 0), e=e, mu=mu, gravity=(0, 0, -G), dt=2e-6,
              quadrature=quadrature)
    sim = lsdem.Simulation(s, threads=2, record_contacts=False)
    end, vend, rise, ts_meas = ts + 0.2, None, 0.0, None
    times, speeds = [], []
    while sim.time < end:
        sim.run(steps=1)
        vx = sim.grains.velocities[0][0]; wy = sim.grains.angular_velocities[0][1]
        if ts_meas is None and vx - R * wy <= 0: ts_meas, vend = sim.time, vx
        if ts_meas is not None and sim.time > ts_meas + 0.02:
            times.append(sim.time); speeds.append(vx)
            rise = max(rise, sim.grains.positions[0][2] - R)
    a = -np.polyfit(times, speeds, 1)[0]
    print(f"slide-to-roll, {quadrature} quadrature, e={e}: slip ends {100*(ts_meas/ts-1):+.1f} %, speed then {100*(vend/vs-1):+.1f} %, "
          f"mu_r {1.4*a/G:.4f}, highest rise {rise:.3g} mm")
# 4. the box dropped flat, time_step auto.
bx = block()
try:
    sim = impact(scene(bx, (0, 0, 2.01), (0, 0, -1000.0), e=0.6), 2.0)
    print(f"box flat, auto step {sim.time_step:.3g} s: ran through the landing")
except lsdem.Error as err:
    print("box flat, auto step: stopped:", str(err).splitlines()[0][:120])
# 5. the box at dt 1e-7, e = 0.3/0.6/0.9.
for e in (0.3, 0.6, 0.9):
    sim = impact(scene(bx, (0, 0, 2.01), (0, 0, -1000.0), e=e, dt=1e-7), 2.0)
    print(f"box e={e}: rebound {100*(sim.grains.velocities[0][2]/1000/e-1):+.2f} %")
# 6. the ball on a wall, e = 0.5/0.9 (3.9 m/s, dt 1e-7).
for e in (0.5, 0.9):
    sim = impact(scene(b, (0, 0, R + 0.005), (0, 0, -3900.0), e=e, dt=1e-7), R)
    print(f"ball e={e}: rebound {sim.grains.velocities[0][2]/3900:.4f} ({100*(sim.grains.velocities[0][2]/3900/e-1):+.2f} %)")

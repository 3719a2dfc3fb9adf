"""Simulations from Python: bit-for-bit equality with lsdem-run, thread independence,
checkpoints, views, callbacks and errors."""

import csv
import subprocess

import numpy as np
import pytest

import lsdem
from conftest import SCENES


def read_grains_csv(path):
    """Positions and velocities from lsdem-run's grains.csv (numbers read back exactly)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    positions = np.array([[float(r[k]) for k in ("x", "y", "z")] for r in rows])
    velocities = np.array([[float(r[k]) for k in ("vx", "vy", "vz")] for r in rows])
    return [r["name"] for r in rows], positions, velocities


def test_equals_lsdem_run_bit_for_bit(lsdem_run, tmp_path):
    # The 27-sphere stack: 3001 steps with walls, many contacts and friction.
    scene_path = SCENES / "cube27.toml"
    subprocess.run([lsdem_run, str(scene_path), "--out", str(tmp_path), "--threads", "2", "-q"],
                   check=True, stdout=subprocess.DEVNULL)
    names, positions, velocities = read_grains_csv(tmp_path / "grains.csv")

    sim = lsdem.Simulation(lsdem.Scene.from_toml(str(scene_path)), threads=2)
    sim.run()
    assert sim.done
    assert sim.grains.names == names
    assert np.array_equal(sim.grains.positions, positions)  # exact, not approximate
    assert np.array_equal(sim.grains.velocities, velocities)


def short_bounce(steps):
    scene = lsdem.Scene.from_toml(str(SCENES / "bounce.toml"))
    scene.end_time = 0.0
    scene.end_steps = steps
    return scene


def test_threads_do_not_change_results():
    # Start low so the ball hits the floor within a few hundred steps.
    text = (SCENES / "bounce.toml").read_text().replace("position = [0, 0, 20]",
                                                        "position = [0, 0, 5.2]")
    scene = lsdem.Scene.from_text(text, str(SCENES / "bounce-low.toml"))
    scene.end_time = 0.0
    scene.end_steps = 600
    one = lsdem.Simulation(scene, threads=1)
    two = lsdem.Simulation(scene, threads=2)
    one.run()
    two.run()
    assert one.threads == 1 and two.threads == 2
    assert np.array_equal(one.grains.positions, two.grains.positions)
    assert np.array_equal(one.grains.orientations, two.grains.orientations)
    assert one.boundaries["floor"].displacement.tolist() == [0.0, 0.0, 0.0]
    assert one.energies == two.energies


def test_dissipation_is_split_by_mechanism():
    # The 27-sphere stack compressed by its walls, with friction, dashpots (e 0.5) and global
    # damping 0.3: each mechanism takes its share, and together they account for what the
    # balance (boundary work less the change of kinetic + elastic energy) says was dissipated,
    # up to the integrator's error (measured 0.3-0.7 % of it over 500-3000 steps).
    scene = lsdem.Scene.from_toml(str(SCENES / "cube27.toml"))
    sim = lsdem.Simulation(scene, threads=2)
    sim.run(steps=2000)
    e = sim.energies
    shares = [e["dissipated_friction"], e["dissipated_dashpot"], e["dissipated_global_damping"]]
    assert all(share > 0.0 for share in shares)
    assert sum(shares) == pytest.approx(e["dissipated"], rel=0.02)


def test_checkpoint_continues_bit_identically(tmp_path):
    straight = lsdem.Simulation(short_bounce(300), threads=2)
    straight.run()

    first = lsdem.Simulation(short_bounce(300), threads=2)
    assert first.run(steps=120) == 120
    first.checkpoint(str(tmp_path / "c.lsdem"))
    resumed = lsdem.Simulation.from_checkpoint(str(tmp_path / "c.lsdem"), threads=1)
    assert resumed.step == 120 and resumed.time == first.time
    assert resumed.run() == 180
    assert np.array_equal(resumed.grains.positions, straight.grains.positions)
    assert np.array_equal(resumed.grains.velocities, straight.grains.velocities)


def test_lsdem_run_restarts_a_python_checkpoint(lsdem_run, tmp_path):
    sim = lsdem.Simulation(short_bounce(200), threads=2)
    sim.run(steps=50)
    sim.checkpoint(str(tmp_path / "checkpoint.lsdem"))
    subprocess.run([lsdem_run, "--restart", str(tmp_path / "checkpoint.lsdem"), "-q"],
                   check=True, stdout=subprocess.DEVNULL)
    sim.run()
    _, positions, _ = read_grains_csv(tmp_path / "grains.csv")
    assert np.array_equal(sim.grains.positions, positions)


def test_views_callbacks_and_state():
    sim = lsdem.Simulation(short_bounce(100), threads=2)
    positions = sim.grains.positions
    assert positions.shape == (1, 3) and positions.dtype == np.float64
    assert not positions.flags.writeable
    start = positions.copy()
    seen = []
    assert sim.run(steps=40, callback=lsdem.every(10, lambda s: seen.append(
        (s.step, s.time, s.kinetic_energy)))) == 40
    assert [step for step, _, _ in seen] == [10, 20, 30, 40]
    assert seen[-1][2] > seen[0][2] > 0.0  # falling faster
    assert positions[0, 2] < start[0, 2]   # the view follows the running world
    assert sim.step == 40 and sim.time == pytest.approx(40 * sim.time_step)
    g = sim.grains
    assert g.velocities.shape == (1, 3) and g.forces.shape == (1, 3)
    assert g.orientations.shape == (1, 4) and g.masses.shape == (1,)
    assert g.angular_velocities.shape == (1, 3)
    contacts = sim.contacts
    assert contacts.points.shape == (0, 3) and contacts.grains.dtype == np.int32
    assert "floor" in sim.boundaries and list(sim.boundaries) == ["floor"]
    assert sim.boundaries["floor"].reaction.shape == (3,)
    with pytest.raises(KeyError, match="floor"):
        sim.boundaries["ceiling"]


def test_contacts_of_a_resting_ball():
    text = (SCENES / "bounce.toml").read_text().replace("position = [0, 0, 20]",
                                                        "position = [0, 0, 4.99]")
    scene = lsdem.Scene.from_text(text, str(SCENES / "resting.toml"))
    scene.gravity = [0, 0, 0]
    sim = lsdem.Simulation(scene, threads=2)
    sim.run(steps=1)
    contacts = sim.contacts
    assert len(contacts.points) > 0 and contacts.forces.shape == contacts.points.shape
    assert np.all(contacts.points[:, 2] < 0.01)
    assert np.all(contacts.grains == 0)
    # The floor's reaction balances the point forces on the ball (walls are not listed).
    assert np.allclose(sim.boundaries["floor"].reaction, -contacts.forces.sum(axis=0))


def test_callback_errors_and_bad_runs():
    sim = lsdem.Simulation(short_bounce(100), threads=1)

    def fail(_):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        sim.run(steps=5, callback=fail)
    assert sim.step == 1
    with pytest.raises(lsdem.Error, match="steps"):
        sim.run(steps=-1)
    with pytest.raises(lsdem.Error, match="threads"):
        lsdem.Simulation(short_bounce(1), threads=0)
    endless = short_bounce(1)
    endless.end_steps = 0
    with pytest.raises(lsdem.Error, match="end condition"):
        lsdem.Simulation(endless, threads=1).run()
    with pytest.raises(lsdem.Error, match="checkpoint|missing|no such"):
        lsdem.Simulation.from_checkpoint("/nonexistent/c.lsdem")


def test_unstable_time_step_raises():
    scene = short_bounce(2000)
    text = (SCENES / "bounce.toml").read_text().replace("position = [0, 0, 20]",
                                                        "position = [0, 0, 4.9]")
    scene = lsdem.Scene.from_text(text, str(SCENES / "unstable.toml"))
    scene.time_step = 1e-3  # far above the stable step of this contact
    with pytest.raises(lsdem.Error, match="step"):
        lsdem.Simulation(scene, threads=1).run(steps=50)


def test_help_is_useful():
    doc = lsdem.Simulation.__doc__
    assert "lsdem-run" in doc and "bit for bit" in doc
    for name in ("run", "checkpoint", "grains", "contacts", "boundaries", "from_checkpoint"):
        assert getattr(lsdem.Simulation, name).__doc__
    for function in (lsdem.bake_mesh, lsdem.bake_sphere, lsdem.load, lsdem.every):
        assert function.__doc__


def test_one_run_at_a_time(tmp_path):
    """A simulation steps one run at a time: a run() or a read of its changing state from
    another thread while it steps, or a run() from its own callback, raises instead of
    corrupting it; its own callback may read it and checkpoint it."""
    import threading
    sim = lsdem.Simulation(short_bounce(100), threads=1)
    from_other_thread = {}

    def other_thread():
        for name, call in (("run", lambda: sim.run(steps=1)),
                           ("energies", lambda: sim.energies),
                           ("contacts", lambda: sim.contacts),
                           ("done", lambda: sim.done),
                           ("checkpoint", lambda: sim.checkpoint(str(tmp_path / "c.lsdem")))):
            try:
                call()
                from_other_thread[name] = None
            except lsdem.Error as error:
                from_other_thread[name] = str(error)

    from_callback = {}

    def callback(s):
        if s.step != 2:
            return
        worker = threading.Thread(target=other_thread)
        worker.start()
        worker.join()  # releases the GIL: the other thread runs while this run is in progress
        with pytest.raises(lsdem.Error, match="own callback"):
            s.run(steps=1)
        from_callback["energies"] = s.energies["kinetic"]
        s.checkpoint(str(tmp_path / "from-callback.lsdem"))

    assert sim.run(steps=5, callback=callback) == 5
    assert from_other_thread["run"] and "another thread" in from_other_thread["run"]
    for name in ("energies", "contacts", "done", "checkpoint"):
        assert from_other_thread[name] and "another thread" in from_other_thread[name], name
    assert from_callback["energies"] > 0.0
    assert (tmp_path / "from-callback.lsdem").exists() and not (tmp_path / "c.lsdem").exists()
    # Over, also after a callback that raised: it runs again.
    with pytest.raises(ZeroDivisionError):
        sim.run(steps=3, callback=lambda s: 1 / 0)
    assert sim.run(steps=2) == 2 and sim.step == 8


def test_threads_are_bounded(tmp_path):
    with pytest.raises(lsdem.Error, match="threads wants a number from 1 to 1024"):
        lsdem.Simulation(short_bounce(1), threads=100000)
    with pytest.raises(lsdem.Error, match="threads"):
        lsdem.run_scene(SCENES / "bounce.toml", tmp_path / "out", threads=5000)
    assert not (tmp_path / "out").exists()


def test_a_pair_of_materials_without_a_law_is_refused(sphere):
    """The reader refuses a scene whose grains could meet without a contact law; a scene built
    in Python is refused too, rather than letting its grains pass through each other."""
    scene = lsdem.Scene()
    scene.add_asset("ball", sphere)
    scene.add_material("steel", density=7.85e-9)
    scene.add_material("wall")
    scene.add_contact("steel", "wall", normal_stiffness=1e3)
    scene.add_grain("ball", "steel", [0, 0, 6])
    scene.add_grain("ball", "steel", [0, 0, 16])
    scene.add_plane("floor", "wall", point=[0, 0, 0], normal=[0, 0, 1])
    with pytest.raises(lsdem.Error, match="no contact law between materials 'steel' and 'steel'"):
        lsdem.Simulation(scene, threads=1)


def test_a_checkpoint_of_an_endless_built_scene_is_refused(sphere, tmp_path):
    """Its scene would be written as a file without an end, which no restart can read."""
    scene = lsdem.Scene()
    scene.add_asset("ball", sphere)
    scene.add_material("steel", density=7.85e-9)
    scene.add_grain("ball", "steel", [0, 0, 6])
    scene.time_step = 1e-5
    sim = lsdem.Simulation(scene, threads=1)
    sim.run(steps=2)
    with pytest.raises(lsdem.Error, match="end_steps"):
        sim.checkpoint(str(tmp_path / "c.lsdem"))
    assert not (tmp_path / "c.lsdem").exists()


def test_a_checkpoint_keeps_the_histories_it_was_restarted_with(lsdem_run, tmp_path):
    """Loaded from lsdem-run's checkpoint and written again, a checkpoint still holds the
    run's histories: lsdem-run --restart writes them out again instead of losing them."""
    result = lsdem.run_scene(SCENES / "bounce.toml", tmp_path, threads=1, stop_at_step=1000)
    before = (tmp_path / "energy.csv").read_text().splitlines()
    sim = lsdem.Simulation.from_checkpoint(result["checkpoint"], threads=1)
    sim.run(steps=100)
    sim.checkpoint(result["checkpoint"])
    subprocess.run([lsdem_run, "--restart", result["checkpoint"], "-q"], check=True,
                   stdout=subprocess.DEVNULL)
    after = (tmp_path / "energy.csv").read_text().splitlines()
    # The rows up to step 1000 are the first run's; the restart's follow from step 1100 on
    # (the 100 steps taken in Python add none).
    assert after[:len(before)] == before
    assert len(after) > len(before)
    assert int(after[len(before)].split(",")[0]) > 1000


def test_contact_pairs_and_micromechanics_agree_with_the_walls_and_numpy():
    """After 300 steps of the 27-sphere stack: each wall's contacts sum to the opposite of its
    reaction (two separate sums in the simulation), normals are unit, the fabrics from the
    grain pairs' normals, branch vectors and normal forces in numpy are micromechanics()'s, and the free grains' stresses add up
    to the stress moment (Σ V_p σ_p, V_p = m_p / ρ)."""
    scene = lsdem.Scene.from_toml(str(SCENES / "cube27.toml"))
    scene.end_time = 0.0
    scene.end_steps = 300
    sim = lsdem.Simulation(scene, threads=2)
    sim.run()
    pairs = sim.contact_pairs
    k = len(pairs.first)
    assert k > 0 and pairs.forces.shape == (k, 3) and pairs.normals.shape == (k, 3)
    assert np.allclose(np.linalg.norm(pairs.normals, axis=1), 1.0, atol=1e-12)
    assert np.all((pairs.second >= 0) != (pairs.boundary >= 0))  # a grain or a boundary
    for index, name in enumerate(sim.boundaries.keys()):
        on_grains = pairs.forces[pairs.boundary == index].sum(axis=0)
        reaction = sim.boundaries[name].reaction
        assert np.allclose(on_grains, -reaction, rtol=1e-12, atol=1e-12 * np.abs(reaction).max())
    m = sim.micromechanics()
    grain = pairs.second >= 0
    n = pairs.normals[grain]
    assert m["grain_contacts"] == int(grain.sum()) and m["free_grains"] == 27
    assert np.allclose(m["fabric"], n.T @ n / len(n), rtol=1e-12, atol=1e-15)
    assert m["fabric"].trace() == pytest.approx(1.0, abs=1e-12)
    # The branch vectors' and the normal forces' fabrics, again in numpy.
    x = sim.grains.positions
    branch = x[pairs.second[grain]] - x[pairs.first[grain]]
    branch /= np.linalg.norm(branch, axis=1)[:, None]
    assert np.allclose(m["branch_fabric"], branch.T @ branch / len(n), rtol=1e-12, atol=1e-15)
    fn = np.abs(np.einsum("ki,ki->k", pairs.forces[grain], n))
    assert np.allclose(m["force_fabric"], (n * fn[:, None]).T @ n / fn.sum(), rtol=1e-12, atol=1e-15)
    assert m["mean_normal_force"] == pytest.approx(fn.mean(), rel=1e-12)
    volumes = sim.grains.masses / 7.85e-9  # cube27.toml's steel
    summed = np.einsum("p,pij->ij", volumes, m["grain_stresses"])
    assert np.allclose(summed, m["stress_moment"], rtol=1e-9, atol=1e-9 * np.abs(summed).max())


def test_nonaffine_displacement_is_falk_and_langers_computed_in_numpy():
    """lsdem.nonaffine_displacement against the definition in numpy on the 27-sphere stack
    between its start and 300 steps later (neighbours within 1.1 of the radii's sum), nil for
    an affine map of the start, and bad shapes refused in lsdem's words."""
    scene = lsdem.Scene.from_toml(str(SCENES / "cube27.toml"))
    scene.end_time = 0.0
    scene.end_steps = 300
    sim = lsdem.Simulation(scene, threads=2)
    start = sim.grains.positions.copy()
    sim.run()
    now = sim.grains.positions
    radii = np.full(len(start), 5.0)  # cube27's spheres
    d2 = lsdem.nonaffine_displacement(start, now, radii)
    expected = []
    for i in range(len(start)):
        near = [j for j in range(len(start))
                if j != i and np.linalg.norm(start[j] - start[i]) < 1.1 * (radii[i] + radii[j])]
        was, is_ = start[near] - start[i], now[near] - now[i]
        j_best = (is_.T @ was) @ np.linalg.pinv(was.T @ was)
        expected.append(((is_ - was @ j_best.T) ** 2).sum() if near else 0.0)
    scale = max(np.max(expected), 1e-300)
    assert np.allclose(d2, expected, rtol=1e-9, atol=1e-9 * scale)
    assert np.max(d2) > 0.0
    a = np.array([[1.01, 0.2, 0.0], [0.0, 0.98, 0.05], [0.03, 0.0, 1.02]])
    assert np.max(lsdem.nonaffine_displacement(start, start @ a.T + 3.0, radii)) < 1e-18
    with pytest.raises(lsdem.Error, match="shape"):
        lsdem.nonaffine_displacement(start[:, :2], now, radii)
    with pytest.raises(lsdem.Error, match="radii"):
        lsdem.nonaffine_displacement(start, now, radii[:-1])


def test_a_periodic_cell_its_unwrapped_positions_and_d2min_across_its_faces(tmp_path):
    """sim.periodic_cell and sim.grains.unwrapped_positions: a sphere streaming through the
    faces of a cell stays inside it while its unwrapped position is start + v·t; a cell strained
    along z has the size (1 + ε̇·dt)^n gives. nonaffine_displacement with the cell's sizes finds
    a face grain's neighbours across it: a grain moved at a face gives its neighbours what one
    moved inside gives its own, one lattice step along."""
    scene_file = tmp_path / "cell.toml"
    scene_file.write_text("""
[assets.ball]
shape = "sphere"
radius = 2.5
voxel = 0.25
nodes = 200

[materials.rock]
density = 2.65e-9

[[contacts]]
materials = ["rock", "rock"]
normal_stiffness = 1e3

[[grains]]
asset = "ball"
material = "rock"
position = [3, 3, 3]
velocity = [700, -300, 200]

[simulation]
time_step = 1e-5
end_steps = 2000
periodic_cell = [12, 12, 12]
periodic_strain_rate = [0, 0, -2]
""")
    sim = lsdem.Simulation(lsdem.Scene.from_toml(str(scene_file)), threads=1)
    sim.run()
    cell = sim.periodic_cell
    assert np.allclose(cell["size"][:2], 12.0)
    assert cell["size"][2] == pytest.approx(12.0 * (1 - 2e-5) ** 2000, rel=1e-12)
    assert np.allclose(cell["strain_rate"], [0, 0, -2])
    x = sim.grains.positions[0]
    assert np.all(x >= 0) and np.all(x < cell["size"])
    # The sphere moved 14, 6 and 4 mm: through the x face at least once, and z carried by the
    # cell's shrinking as well (its unwrapped z is the start plus v_z·t, scaled with the cell).
    unwrapped = sim.grains.unwrapped_positions[0]
    assert unwrapped[0] == pytest.approx(3 + 700 * 0.02, rel=1e-9)
    assert unwrapped[1] == pytest.approx(3 - 300 * 0.02, rel=1e-9)
    assert not np.allclose(unwrapped, x)
    plain = lsdem.Simulation(lsdem.Scene.from_toml(str(SCENES / "cube27.toml")), threads=1)
    assert plain.periodic_cell is None

    # D²min on a 4 × 4 × 4 lattice in a cell of 4, stretched, one grain moved off the field.
    site = np.array([(a, b, c) for a in range(4) for b in range(4) for c in range(4)], float) + 0.5
    stretch = np.array([1.05, 0.97, 0.9])
    now = site * stretch
    radii = np.full(len(site), 0.5)
    sizes = dict(reference_size=[4, 4, 4], current_size=4 * stretch)
    assert np.max(lsdem.nonaffine_displacement(site, now, radii, **sizes)) < 1e-24
    index = {tuple(s - 0.5): k for k, s in enumerate(site)}
    u = np.array([0.03, -0.02, 0.01])
    inside, at_face = now.copy(), now.copy()
    inside[index[(1, 1, 1)]] += u
    at_face[index[(0, 1, 1)]] += u
    d_inside = lsdem.nonaffine_displacement(site, inside, radii, **sizes)
    d_face = lsdem.nonaffine_displacement(site, at_face, radii, **sizes)
    assert d_face[index[(0, 1, 1)]] == pytest.approx(6 * u @ u, rel=1e-9)
    for (a, b, c), k in index.items():
        assert d_face[k] == pytest.approx(d_inside[index[((a + 1) % 4, b, c)]], abs=1e-15)
    assert d_face[index[(3, 1, 1)]] > 0.1 * u @ u  # the neighbour across the x face
    assert lsdem.nonaffine_displacement(site, at_face, radii)[index[(3, 1, 1)]] < 1e-24
    with pytest.raises(lsdem.Error, match="give its reference_size too"):
        lsdem.nonaffine_displacement(site, now, radii, current_size=[4, 4, 4])
    with pytest.raises(lsdem.Error, match="period along x"):
        lsdem.nonaffine_displacement(site, now, radii, reference_size=[2, 4, 4])
    with pytest.raises(lsdem.Error, match="different axes"):
        lsdem.nonaffine_displacement(site, now, radii, reference_size=[4, 4, 4],
                                     current_size=[4, 4, 0])

"""lsdem: the level-set discrete element method (LS-DEM) from Python.

Grain assets (bake_mesh, bake_sphere, bake_box, bake_ellipsoid, load; Asset.sample),
scenes (Scene.from_toml, Scene.to_toml, or built with Scene.add_*), simulations
(Simulation.run, .grains, .contacts, .boundaries, .checkpoint), whole runs as lsdem-run
performs them (run_scene) and the paper's studies (study.two_spheres). Arrays are numpy; errors are
lsdem.Error with lsdem's message (where, problem, fix). Units are yours: lsdem never converts.
See docs/python.md.
"""

from ._lsdem import (  # noqa: F401  (re-exported)
    Asset,
    Boundaries,
    Boundary,
    Error,
    Grains,
    Nodes,
    Scene,
    Simulation,
    bake_box,
    bake_ellipsoid,
    bake_mesh,
    bake_sphere,
    load,
    nonaffine_displacement,
    run_scene,
    study,
)

__all__ = [
    "Asset", "Boundaries", "Boundary", "Error", "Grains", "Nodes", "Scene", "Simulation",
    "bake_box", "bake_ellipsoid", "bake_mesh", "bake_sphere", "load", "every",
    "nonaffine_displacement", "run_scene", "study",
]

# Show the public classes as lsdem.X (not lsdem._lsdem.X) in help() and reprs.
for _name in ("Asset", "Boundaries", "Boundary", "Error", "Grains", "Nodes", "Scene",
              "Simulation"):
    globals()[_name].__module__ = "lsdem"
del _name


def every(n, function):
    """A Simulation.run callback that calls function(sim) every n steps (when sim.step is a
    multiple of n), e.g. sim.run(steps=1000, callback=lsdem.every(100, print_energy))."""
    if n < 1:
        raise ValueError("every(n, ...) wants n >= 1")

    def callback(sim):
        if sim.step % n == 0:
            function(sim)

    return callback

"""Scene files (TOML) and the built-in scenes.

Format (all SI units; see ``cogiro.toml`` for a complete example)::

    [scene]           name, description, g [m/s^2]
    [platform]        mass [kg], center_of_mass [m], inertia [kg m^2] (tensor about G,
                      off-diagonal = -product of inertia), free_dofs (subset of
                      x y z rx ry rz)
    [cable]           default cable: mass_per_length [kg/m], EA [N], viscous_damping
                      [N s/m^2], loss_factor [-]
    [tension_limits]  min, max [N]
    [[cables]]        one table per cable: anchor [m, base], attachment [m, platform],
                      optionally any [cable] key to override it for this cable
    [pose]            optional: position [m], rotation [rad] (rotation vector), or
                      unstretched_lengths [m] (one per cable)
    [analysis]        optional: band_hz [Hz, Hz] (band of interest), n_modes,
                      forbidden_band_hz [Hz, Hz] (no platform mode in it: design checks),
                      model (rung: spring, catenary, dsm, lumped; default dsm), model_rtol
                      [-] (admissible frequency error of the model, default 0.01), segments
                      (lumped rung, default 30)
    [damping]         optional, added to the cables' own damping in every analysis:
                      platform_ratio [-] (modal damping ratio of the platform modes,
                      default 0.01), cable_loss_factor [-] (hysteretic, all cable motions,
                      default 0.01), cable_viscous_damping [N s/m^2] (default 0); zeros:
                      undamped
    [study]           optional, free-form: parameters of the scene's validation study
                      (trajectory, excitation, drums ...), as ``Scene.study`` (a dict)
    [workspace]       optional: box [m] (x0, x1, y0, y1, z0, z1 of P), the default box of
                      a workspace map (``dynstiff workspace``)
    [[trajectories]]  optional, one table per path of the platform through waypoints
                      (:class:`dynstiff.WaypointPath`): name, law (linear, cubic, quintic,
                      parabolic_blend), times [s], positions [m], rotations [rad] (rotation
                      vectors, default 0), velocities [m/s] and accelerations [m/s^2] of P
                      (cubic, quintic; default 0), blend_times [s] (parabolic_blend); as
                      ``Scene.trajectories`` (a dict by name), followed by ``dynstiff sweep
                      --trajectory`` and ``dynstiff simulate --trajectory``

Unknown keys, missing keys and bad values raise :class:`SceneError` naming the key and its line.
Values are taken as written, never coerced: numbers are numbers (not strings, not booleans),
points are 3 numbers, ``free_dofs`` is a list of names, and ``[pose]`` gives a position or
unstretched lengths, not both.
"""

from dynstiff.scenes.caspr import import_caspr
from dynstiff.scenes.loader import Scene, SceneError, list_scenes, load_scene, read_scene
from dynstiff.scenes.writer import scene_text, write_scene

__all__ = ["Scene", "SceneError", "list_scenes", "load_scene", "read_scene", "import_caspr",
           "scene_text", "write_scene"]

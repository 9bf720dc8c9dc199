"""sphys: rigid-body collision handling with sphere-trees, from Python.

Everything the command line does, by task (docs/python.md):

* meshes: load_mesh, load_model("bunny"), check_mesh, decimate, normalize, mass_properties,
  box, icosphere, torus; Mesh(vertices, triangles)
* sphere-trees: build_tree, build_methods, read_sph, write_sph, tree_quality, sphere_quality;
  SphereTree (centres, radii, level(k))
* worlds: World(**settings), settings_table, World.add_body / step / poses / velocities /
  contacts; StepStats
* joints: World.add_joint(JointDesc(...)) / remove_joint / joint_state / set_joint_motor /
  set_joint_limit / set_joint_spring; JointType, JointLimit, JointMotor, JointSpring, JointCone,
  JointId, JointState
* queries: World.query() (a WorldQuery: cast_ray, cast_ray_all, cast_rays, overlap_sphere /
  aabb / box / body, distance, check_configurations), World.check_configurations, QueryFilter
* scenes: load_scene("stacks:4x50" or a file), Scene.from_dict, Simulation(scene).step / run /
  summary; read_recording, RecordingWriter (poses, or a Simulation or World with its robots)
* robots: load_robot_model, robot_model_from_text; World.add_robot (a Robot driven by position,
  velocity or torque control)
* the experiment: run_experiment_row, paper_table, paper_statistics, experiment_statistics,
  sphys.experiment.table (a pandas DataFrame when pandas is installed)
* sweeps on Dask: sphys.sweep.sweep (and `python3 -m sphys.sweep`)

sphys.__version__ is the library's version (CHANGES.md), as `sphys --version` says it.

Units are SI throughout: metres, seconds, kilograms, radians. Quaternions are (x, y, z, w).
Bad input raises sphys.Error (a ValueError) with the command line's message.
"""

from ._sphys import *  # noqa: F401,F403  (the native module's whole API)
from ._sphys import Error  # noqa: F401  (named, for readers and linters)
from ._sphys import __version__  # noqa: F401  (include/sphys/version.h; `*` skips it)
from .robot_files import robot_model_from_text  # noqa: F401

"""A robot written from text: its URDF and its spheres saved as files, then loaded.

As MuJoCo's MjModel.from_xml_string makes a model from a string, robot_model_from_text makes a
RobotModel from a URDF's text, for robots written in the script that simulates them. The files
stay where they are written: a recording of a world holding the robot (RecordingWriter) names
them, and `sphys view` reads them to draw its links.
"""

from pathlib import Path

from ._sphys import load_robot_model


def spheres_yaml(spheres):
    """cuRobo's sphere file (collision_spheres) for {link: [((x, y, z), radius), ...]}, in
    metres in each link's frame; every number written so that it reads back bit for bit."""
    lines = ["collision_spheres:"]
    for link, link_spheres in spheres.items():
        lines.append(f"  {link}:")
        for centre, radius in link_spheres:
            x, y, z = (float(c) for c in centre)
            lines.append(f"    - center: [{x!r}, {y!r}, {z!r}]")
            lines.append(f"      radius: {float(radius)!r}")
    return "\n".join(lines) + "\n"


def robot_model_from_text(urdf, spheres, folder, name="robot"):
    """A RobotModel from a URDF's text and its spheres ({link: [((x, y, z), radius), ...]}, m),
    written to folder/NAME.urdf and folder/NAME.yml (cuRobo's format) and loaded with
    load_robot_model. The folder is made if missing; the files are replaced if there."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    urdf_path = folder / f"{name}.urdf"
    spheres_path = folder / f"{name}.yml"
    urdf_path.write_text(urdf)
    spheres_path.write_text(spheres_yaml(spheres))
    return load_robot_model(urdf_path, spheres_path)

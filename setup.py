"""`pip install .`: the package python/sphys with its native module _sphys, which CMake builds.

The module comes from the release build tree (build/release, the release preset): pip runs
`cmake --build` of its one target there, so a tree where it is already up to date (after
`scripts/test` or a developer's build) is reused as it is, and a fresh clone builds it once.
The version is include/sphys/version.h's.
"""

import os
import re
import shutil
import subprocess
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
BUILD_DIR = ROOT / "build" / "release"


def version():
    text = (ROOT / "include" / "sphys" / "version.h").read_text()
    parts = []
    for part in ("MAJOR", "MINOR", "PATCH"):
        match = re.search(rf"^#define SPHYS_VERSION_{part} (\d+)$", text, re.MULTILINE)
        if not match:
            raise SystemExit(f"setup.py: include/sphys/version.h defines no SPHYS_VERSION_{part}")
        parts.append(match.group(1))
    return ".".join(parts)


def configured_with_module():
    cache = BUILD_DIR / "CMakeCache.txt"
    return cache.is_file() and "SPHYS_BUILD_PYTHON:BOOL=ON" in cache.read_text()


class CMakeBuild(build_ext):
    """Builds _sphys with CMake and copies it where the wheel takes it from."""

    def build_extension(self, ext):
        # The preset configures only a tree that lacks the module (none yet, or scripts/demo's),
        # so that a developer's settings stay as they are.
        if not configured_with_module():
            subprocess.run(["cmake", "--preset", "release"], cwd=ROOT, check=True)
        jobs = os.environ.get("SPHYS_JOBS", str(os.cpu_count() or 1))
        subprocess.run(
            ["cmake", "--build", str(BUILD_DIR), "-j", jobs, "--target", "sphys_python"],
            cwd=ROOT,
            check=True,
        )
        built = BUILD_DIR / "python" / "sphys" / ("_sphys" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.is_file():
            raise SystemExit(
                f"setup.py: {built} is missing: the module is built for the Python CMake found "
                "(Debian's /usr/bin/python3 unless -DPython_EXECUTABLE says otherwise), which is "
                "not the one running pip"
            )
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(
    version=version(),
    ext_modules=[Extension("sphys._sphys", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)

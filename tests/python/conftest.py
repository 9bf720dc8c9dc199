"""Shared fixtures of the sphys pytest suites.

Run with Debian's Python (the one with numpy), against the package in the build tree:

    PYTHONPATH=build/release/python SPHYS_CLI=build/release/bin/sphys \
        /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python
"""

import json
import os
import pathlib
import subprocess
import sys
import threading

import pytest

import sphys

REPO = pathlib.Path(__file__).resolve().parents[2]


def cli_path():
    """The command-line binary: $SPHYS_CLI, else the release build's."""
    return pathlib.Path(os.environ.get("SPHYS_CLI", REPO / "build" / "release" / "bin" / "sphys"))


@pytest.fixture(scope="session")
def cli():
    """Runs `sphys ARGS...` and returns the CompletedProcess (text mode, never raising)."""
    path = cli_path()
    if not path.is_file():
        pytest.skip(f"the sphys command line is not built ({path})")

    def run(*args, timeout=120, env=None):
        return subprocess.run([str(path), *map(str, args)], capture_output=True, text=True,
                              timeout=timeout, env=None if env is None else {**os.environ, **env})

    return run


@pytest.fixture(scope="session")
def simulate_cli(cli, tmp_path_factory):
    """`sphys simulate SCENE --frames N [--set ...] --out DIR --json`, cached per arguments for the
    session: returns (summary dict, recording path)."""
    cache = {}

    def run(scene, frames, *settings):
        key = (scene, frames, settings)
        if key not in cache:
            out = tmp_path_factory.mktemp("simulate")
            args = ["simulate", scene, "--frames", frames, "--out", out, "--json"]
            for setting in settings:
                args += ["--set", setting]
            done = cli(*args)
            assert done.returncode == 0, done.stderr
            cache[key] = (json.loads(done.stdout), out / "recording.sphysrec")
        return cache[key]

    return run


def run_isolated(code, timeout=120):
    """Runs Python `code` in a fresh interpreter (this one, with this environment), for checks
    that may crash the interpreter: a crash then fails one test instead of ending the session.
    Returns the CompletedProcess."""
    return subprocess.run([sys.executable, "-X", "faulthandler", "-c", code], capture_output=True,
                          text=True, timeout=timeout)


def assert_isolated(code, timeout=120):
    """run_isolated(code) must exit 0; its output is shown otherwise (a negative return code is
    the signal that killed it, -11 a segmentation fault)."""
    done = run_isolated(code, timeout)
    assert done.returncode == 0, (
        f"the snippet exited with {done.returncode}\n--- stdout\n{done.stdout}\n--- stderr\n"
        f"{done.stderr}")
    return done


def run_side_by_side(work):
    """Runs work(0) and work(1) on two threads at once. With a switch interval of 1000 s a thread
    that holds the GIL keeps it until it blocks or releases it, so the two calls can overlap in
    time only where the library released the GIL."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
    finally:
        sys.setswitchinterval(old)


@pytest.fixture
def side_by_side():
    """run_side_by_side, for tests."""
    return run_side_by_side


@pytest.fixture
def isolated():
    """assert_isolated, for tests."""
    return assert_isolated


@pytest.fixture
def sphere_tree():
    """A factory of one-node sphere-trees: a sphere of `radius` (m) centred on the body's
    origin."""

    def make(radius=0.5):
        return sphys.SphereTree.from_arrays([[0.0, 0.0, 0.0]], [radius], [-1], 8)

    return make

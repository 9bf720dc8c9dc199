"""Every public class, function, method and property of the package has a docstring, and those
whose name says they hold a physical quantity say its unit."""

import inspect
import re
import types

import sphys
import sphys.experiment
import sphys.sweep

# Names that hold a physical quantity: their docstrings must name its unit.
QUANTITY = re.compile(r"position|velocit|speed|gravity|distance|radius|radii|gap|protrusion|"
                      r"penetration|height|size|mass|inertia|density|volume|energy|time_step|"
                      r"impulse|force|torque|dt\b|hertz")
# A unit as the docs write them: "unit: m/s", "(m)", "in m", "metres", "kg/m^3", ...
UNIT = re.compile(r"unit|\((m|s|kg|rad|J|N|Hz|ms|m/s|m/s²|rad/s)[,)]|\b(m|s|kg|rad|J|Hz|m/s|"
                  r"m/s²|rad/s|kg/m³|kg/m\^3|kg·m²|m³|m²|N|N·m|N·s)\b|metres|seconds|radians|"
                  r"dimensionless|count")


def own_text(obj):
    """The docstring less the signature lines pybind11 writes itself."""
    name = getattr(obj, "__name__", "")
    lines = (getattr(obj, "__doc__", None) or "").splitlines()
    signature = re.compile(rf"^\s*(\d+\.\s*)?{re.escape(name)}\(")
    return "\n".join(line for line in lines
                     if not signature.match(line) and line.strip() != "Overloaded function."
                     ).strip()


def public_members(owner):
    for name, value in vars(owner).items():
        if name.startswith("_") and name != "__init__":
            continue
        yield name, value


def problems(modules):
    """What is missing, one line each, in the public names of `modules` (a package first)."""
    found = []

    def check(path, obj, text):
        if not text:
            found.append(f"{path}: no docstring")
        elif QUANTITY.search(path.rsplit(".", 1)[-1]) and not UNIT.search(text):
            found.append(f"{path}: the docstring names no unit: {text!r}")

    def walk_class(path, cls):
        check(path, cls, own_text(cls))
        for name, value in public_members(cls):
            if isinstance(value, property):
                check(f"{path}.{name}", value, (value.__doc__ or "").strip())
            elif inspect.isclass(value):
                walk_class(f"{path}.{name}", value)
            elif callable(value) and not isinstance(value, cls):  # enum values are instances
                check(f"{path}.{name}", value, own_text(value))

    for module in modules:
        for name in dir(module):
            value = getattr(module, name)
            if name.startswith("_") or inspect.ismodule(value):
                continue
            # Names a module imports from elsewhere are checked where they are defined.
            home = getattr(value, "__module__", module.__name__) or ""
            if module is not modules[0] and not home.startswith(module.__name__):
                continue
            if inspect.isclass(value):
                walk_class(f"{module.__name__}.{name}", value)
            elif callable(value):
                check(f"{module.__name__}.{name}", value, own_text(value))
    return found


def test_every_public_name_has_a_docstring_with_its_units():
    found = problems([sphys, sphys.experiment, sphys.sweep])
    assert not found, f"{len(found)} without a docstring or its unit:\n" + "\n".join(found)


def test_the_walk_finds_what_is_missing():
    module = types.ModuleType("planted")

    class Body:
        """A body."""

        def push(self):
            pass

        @property
        def mass(self):
            """How heavy it is."""

    def documented():
        """Documented."""

    module.Body, module.documented = Body, documented
    Body.__module__ = documented.__module__ = "planted"
    assert problems([module]) == [
        "planted.Body.push: no docstring",
        "planted.Body.mass: the docstring names no unit: 'How heavy it is.'",
    ]

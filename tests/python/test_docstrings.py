"""Every class, function, method and property of the module says what it does (help(dnurbs.X)
is useful): its docstring has text beyond pybind11's generated signature."""

import inspect

import dnurbs


def described(doc, name):
    """True if `doc` has a line that is not pybind11's signature of `name` ("name(self: ...) ->
    ...", "(self: ...) -> ..." for properties, "1. name(...)" for overloads)."""
    if not doc:
        return False
    short = name.split(".")[-1]
    for line in (line.strip() for line in doc.splitlines()):
        if line.split(". ", 1)[-1].startswith((f"{short}(", "(self")):
            continue
        if line and not line.startswith("Overloaded function"):
            return True
    return False


def public_members():
    for name, value in vars(dnurbs._dnurbs).items():
        if name.startswith("_"):
            continue
        yield name, value
        if inspect.isclass(value):
            for member, attribute in vars(value).items():
                if member.startswith("_") and member not in ("__init__", "__call__"):
                    continue
                if hasattr(value, "__members__") and member in ("name", "value", "__init__"):
                    continue  # pybind11's own enum members
                yield f"{name}.{member}", attribute


def test_every_public_name_has_a_docstring():
    missing = []
    for name, value in public_members():
        if isinstance(value, (int, float, str)) or hasattr(type(value), "__members__"):
            continue  # enum values
        if not described(value.__doc__, name):
            missing.append(name)
    assert missing == []

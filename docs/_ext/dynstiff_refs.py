"""Cross-references in the package's docstrings, resolved as Python resolves names.

The docstrings name objects where they are defined (``dynstiff.models.ladder.build_model``)
or in the scope of their module (``Robot.equilibrium``, ``ClosedFormWarning``), while the
reference documents each object once, under its public name (``dynstiff.build_model``). A
reference that Sphinx cannot resolve is looked up by importing it (in the module and class of
the docstring first, then in ``dynstiff``): an object that has a page under another name is
linked there; a real object without a page (a private module, a helper) is shown as text; a
name that imports nothing keeps its warning, so a stale reference still fails the build.
"""

import importlib
import inspect

from sphinx.util import logging

logger = logging.getLogger(__name__)

_MISSING = object()


class _Field:
    """A dataclass field (no class attribute of its own)."""

    def __init__(self, owner):
        self.owner = owner


def import_object(name):
    """The object a dotted name refers to, or ``_MISSING``."""
    parts = name.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        except Exception:  # a module failing for another reason is not a target
            return _MISSING
        for attr in parts[i:]:
            if inspect.isclass(obj):
                owner = obj
                obj = inspect.getattr_static(obj, attr, _MISSING)
                if obj is _MISSING and attr in getattr(owner, "__dataclass_fields__", ()):
                    return _Field(owner)      # a field: documented on its class's page
            else:
                obj = getattr(obj, attr, _MISSING)
            if obj is _MISSING:
                return _MISSING
        return obj
    return _MISSING


def _unwrap(obj):
    if isinstance(obj, (staticmethod, classmethod)):
        return obj.__func__
    return obj


def _key(obj):
    """Identity of objects that have one name (classes, functions, modules, descriptors)."""
    obj = _unwrap(obj)
    if inspect.isclass(obj) or inspect.isroutine(obj) or inspect.ismodule(obj) \
            or isinstance(obj, property) or hasattr(obj, "__get__"):
        return id(obj)
    return None


def _documented(app, env):
    """``{id(object): (full name, object type)}`` of the documented objects (kept on the
    application, not in the pickled environment: identities hold within one process)."""
    cache = getattr(app, "_dynstiff_documented", None)
    if cache is None:
        cache = {}
        for name, entry in env.get_domain("py").objects.items():
            obj = import_object(name)
            if obj is _MISSING:
                continue
            key = _key(obj)
            if key is not None and (key not in cache or len(name) < len(cache[key][0])):
                cache[key] = (name, entry.objtype)
            # data: known by value and last name (a tuple of rung names, a constant)
            cache.setdefault(("data", name.rsplit(".", 1)[-1], repr(obj)[:200]),
                             (name, entry.objtype))
        app._dynstiff_documented = cache
    return cache


def _defining_scopes(node):
    """Module (and class) where the documented object is defined: a docstring's names are
    those of its own module."""
    doc = node.get("refdoc", "")
    if "/generated/" not in doc:
        return []
    obj = import_object(doc.rsplit("/", 1)[-1])
    if obj is _MISSING:
        return []
    obj = _unwrap(obj)
    module = getattr(obj, "__module__", None)
    if inspect.ismodule(obj):
        return [obj.__name__]
    if not module:
        return []
    scopes = [module]
    if inspect.isclass(obj):
        scopes.insert(0, f"{module}.{obj.__qualname__}")
    return scopes


def _candidates(node):
    target = node["reftarget"].lstrip(".~")
    module, cls = node.get("py:module"), node.get("py:class")
    if target.startswith("dynstiff"):
        return [target]
    names = []
    if module and cls:
        names.append(f"{module}.{cls}.{target}")
    if module:
        names.append(f"{module}.{target}")
    names += [f"{scope}.{target}" for scope in _defining_scopes(node)]
    names.append(f"dynstiff.{target}")
    return names


def resolve(app, env, node, contnode):
    if node.get("refdomain") != "py":
        return None
    domain = env.get_domain("py")
    documented = _documented(app, env)
    for name in _candidates(node):
        obj = import_object(name)
        if obj is _MISSING:
            continue
        if isinstance(obj, _Field):
            obj = obj.owner
        key = _key(obj)
        hit = documented.get(key) if key is not None else \
            documented.get(("data", name.rsplit(".", 1)[-1], repr(obj)[:200]))
        if hit is not None:
            ref = domain.resolve_any_xref(env, node["refdoc"], app.builder, hit[0], node,
                                          contnode)
            if ref:
                return ref[0][1]
        return contnode             # a real object without a page: text, no link
    return None


def setup(app):
    app.connect("missing-reference", resolve, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}

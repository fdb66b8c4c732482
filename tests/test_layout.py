"""The package's shape: the public ``gearkit`` names, and which module may import which.

``PUBLIC`` is the table of ``gearkit/__init__.py`` as it stood before the layout change
(issue 12): a name may be added, none may disappear or move out of ``import gearkit``. The import
checks walk the source of ``gearkit/`` (every ``import``, lazy ones inside functions included):
dependencies point down the layers of ``LAYERS``, no two modules import each other (directly or
round a loop), and no module imports another module's ``_private`` name.
"""
import ast
from pathlib import Path

import gearkit

#: every public name of ``import gearkit`` (the lazy table plus the three errors)
PUBLIC = (
    "Accuracy", "ArcRack", "ArcSpec", "Assembly", "BasicRack", "BlockingAtlas", "BlockingContour", "CheckLimits",
    "CheckReport", "ContactAnalysis", "CycloidGear", "CycloidPairSpec", "CycloidalDisc", "DriveSpec", "Finding",
    "GearSpec", "GearkitError", "GeometryError", "InvoluteProfile", "NovikovCheck", "NovikovGearSpec",
    "NovikovLimits", "NovikovPairGeometry", "NovikovPairSpec", "NovikovProfile", "PairCheck", "PairGeometry",
    "PairSpec", "PinGearSpec", "PinGearWheel", "RackProfile", "RackSpec", "RackSystem", "ShaperCutter", "Solid",
    "SolidSpec", "SpecError", "ToothProfile", "analyse_pair", "blocking_atlas", "blocking_contour",
    "check_cycloid_pair", "check_drive", "check_novikov", "check_pair", "check_pin_gearing", "cycloid_gear",
    "disc_profile", "gear_solid", "load_design", "load_rack_system", "mesh_contact", "meshed_outlines",
    "novikov_pair_geometry", "novikov_tooth_profile", "pair_assembly", "pair_geometry", "pin_gear_wheel", "pin_ring",
    "rack_presets", "rack_profile", "rack_solid", "rack_system", "run_bench", "shifts_for_center_distance",
    "simulate_mesh", "swept_gear", "tooth_profile", "write_mesh",
)


def test_every_public_name_is_still_exported_and_resolves():
    missing = [n for n in PUBLIC if n not in gearkit.__all__]
    assert missing == []
    unresolved = [n for n in PUBLIC if getattr(gearkit, n, None) is None]
    assert unresolved == []


def test_public_names_are_the_families_own_objects():
    from gearkit.families.involute.gear import tooth_profile
    from gearkit.families.novikov.gear import tooth_profile as novikov_tooth_profile

    assert gearkit.tooth_profile is tooth_profile
    assert gearkit.novikov_tooth_profile is novikov_tooth_profile
    assert gearkit.RackSpec.__module__ == "gearkit.families.involute.rack"


# ----------------------------------------------------------------------------- import direction

PACKAGE = Path(__file__).resolve().parent.parent / "gearkit"

#: the layers, bottom first: a module may import only from its own layer or a lower one
LAYERS = (
    ("base", ("gearkit", "gearkit.errors", "gearkit.accuracy", "gearkit.distances", "gearkit.chords", "gearkit.curves",
              "gearkit.export", "gearkit.refine", "gearkit.roots", "gearkit.progress", "gearkit.values")),
    ("kernel", ("gearkit.segments", "gearkit.motion", "gearkit.envelope", "gearkit.pieces", "gearkit.boundary",
                "gearkit.profile")),
    ("families", ("gearkit.families", "gearkit.oracles")),  # every family package, and their oracles
    ("pair", ("gearkit.pair",)),
    ("checks/contact", ("gearkit.checks", "gearkit.contact")),
    ("blocking/solids/scene", ("gearkit.blocking", "gearkit.solids", "gearkit.scene")),
    ("cli/bench/view", ("gearkit.cli", "gearkit.bench", "gearkit.view", "gearkit.__main__")),
)
#: the envelope path, which the oracles must not import (they are its independent check)
ENVELOPE_PATH = ("gearkit.segments", "gearkit.motion", "gearkit.envelope", "gearkit.pieces", "gearkit.boundary",
                 "gearkit.profile")


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _is_module(name: str) -> bool:
    rel = Path(*name.split("."))
    return (PACKAGE.parent / rel).with_suffix(".py").is_file() or (PACKAGE.parent / rel / "__init__.py").is_file()


def _layer(module: str) -> int:
    """Index of ``module``'s layer (the longest matching prefix); ValueError for an unplaced module."""
    best = None
    for i, (_, prefixes) in enumerate(LAYERS):
        for p in prefixes:
            if (module == p or module.startswith(p + ".")) and (best is None or len(p) > best[1]):
                best = (i, len(p))
    if best is None or (best[1] == len("gearkit") and module != "gearkit"):
        raise ValueError(f"{module} is in no layer of LAYERS: add it")
    return best[0]


def _imports(path: Path):
    """(target module, imported name or None, line) of every gearkit import in ``path``, lazy ones included."""
    tree = ast.parse(path.read_text(), str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "gearkit":
                    yield a.name, None, node.lineno
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] == "gearkit":
            assert node.level == 0, f"{path}:{node.lineno}: relative import"
            for a in node.names:
                sub = f"{node.module}.{a.name}"
                if _is_module(sub):
                    yield sub, None, node.lineno
                else:
                    yield node.module, a.name, node.lineno


def _graph():
    graph = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        graph[_module_name(path)] = (path, list(_imports(path)))
    return graph


def _cycles(edges: dict) -> list:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def test_every_module_has_a_layer():
    for module in _graph():
        _layer(module)


def test_imports_point_down_the_layers():
    upward = []
    for module, (path, imports) in _graph().items():
        for target, _, line in imports:
            if _layer(target) > _layer(module):
                upward.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {module} "
                              f"({LAYERS[_layer(module)][0]}) imports {target} ({LAYERS[_layer(target)][0]})")
    assert upward == []


def test_no_import_cycles_between_modules():
    graph = _graph()
    edges = {m: {t for t, _, _ in imports if t != m} for m, (_, imports) in graph.items()}
    assert _cycles(edges) == []


def test_no_private_name_is_imported_from_another_module():
    private = []
    for module, (path, imports) in _graph().items():
        for target, name, line in imports:
            if target != module and ((name or "").startswith("_") or target.rsplit(".", 1)[-1].startswith("_")):
                private.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {name or target} from {target}")
    assert private == []


def test_the_oracles_import_nothing_of_the_envelope_path():
    graph = _graph()
    bad = [f"{m} imports {t}" for m, (_, imports) in graph.items() if m.startswith("gearkit.oracles")
           for t, _, _ in imports if any(t == p or t.startswith(p + ".") for p in ENVELOPE_PATH)]
    assert bad == []


def test_the_checker_catches_what_it_is_for():
    """The checks above see real violations: a cycle, an upward import, an unplaced module."""
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []
    assert _layer("gearkit.families.cam.profile") == _layer("gearkit.families.novikov") == 2
    assert _layer("gearkit.scene.train") == _layer("gearkit.solids.gear") > _layer("gearkit.contact")
    assert _layer("gearkit.cli.gear") > _layer("gearkit.blocking")
    try:
        _layer("gearkit.newthing")
    except ValueError:
        pass
    else:
        raise AssertionError("an unplaced module was given a layer")


def test_no_module_is_over_400_lines():
    long = {str(p.relative_to(PACKAGE.parent)): n for p in PACKAGE.rglob("*.py")
            if (n := len(p.read_text().splitlines())) > 400}
    assert long == {}


# ----------------------------------------------------------------------------- one CLI vocabulary

#: flags every command spells the same way: declared only through gearkit/cli/common.py
SHARED_FLAGS = ("-o", "--output", "--tol", "--json", "-m", "--module", "-z", "--teeth", "-x", "--shift", "--keyway",
                "--progress")
#: known exceptions (module, flag), each with its reason; none today
CLI_EXCEPTIONS = set()


def test_the_shared_cli_flags_are_declared_only_in_cli_common():
    import re

    declared = re.compile(r"""add_argument\(\s*["'](-[-\w]+)["']""")
    offenders = []
    for path in sorted((PACKAGE / "cli").glob("*.py")):
        if path.name == "common.py":
            continue
        for flag in declared.findall(path.read_text()):
            if flag in SHARED_FLAGS and (path.name, flag) not in CLI_EXCEPTIONS:
                offenders.append(f"{path.name}: {flag}")
    assert offenders == []
    common = (PACKAGE / "cli" / "common.py").read_text()
    assert all(f'"{flag}"' in common for flag in ("-o", "--tol", "--json", "-m", "-z", "-x", "--progress"))

"""The comparison layer's layout holds: the order of its jobs that `comparisons/__init__.py`
states, no import cycle, one matplotlib importer, one caller of the roads.  And `analytic`'s: the
independent references (`analytic/references/`) import neither `bem` nor the paper's road, the
road does not import them, and each reference stands alone.  Function-level imports count: a lazy
import is still an arrow."""
import ast
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
PKG = ROOT / "comparisons"


def _modules():
    out = {}
    for path in PKG.rglob("*.py"):
        if "data" in path.relative_to(PKG).parts:
            continue
        parts = list(path.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _imports(name, path):
    """(absolute targets of every import in the module, top level or not)."""
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            yield from (a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module
            yield mod
            yield from (f"{mod}.{a.name}" for a in node.names)


def _arrows():
    """module -> the comparisons modules it imports."""
    out = {}
    for name, path in MODULES.items():
        targets = set()
        for t in _imports(name, path):
            while t and t not in MODULES:
                t = t.rpartition(".")[0]
            if t and t != name and not name.startswith(t + "."):
                targets.add(t)
        out[name] = targets
    return out


def _floors():
    """The jobs' lines of the package docstring, top to bottom: [{first path part, ...}, ...]."""
    doc = ast.get_docstring(ast.parse((PKG / "__init__.py").read_text(encoding="utf-8")))
    section = doc.split("Where each job lives", 1)[1].split("\n\n")[1]  # the list
    floors = []
    for item in re.split(r"\n- ", "\n" + section.strip()):
        head = item.split(":", 1)[0]
        names = {n.rstrip("/") for n in re.findall(r"``([\w/]+)``", head)}
        if names:
            floors.append(names)
    return floors


def test_the_stated_floors_name_every_module():
    floors = _floors()
    assert len(floors) >= 5
    named = set().union(*floors) | {"bench"}  # beside the floors, said after them
    for name in MODULES:
        parts = name.split(".")
        if len(parts) > 1:
            assert parts[1] in named, f"{name} is in no line of comparisons/__init__.py"


def test_no_module_imports_a_job_stated_above_it():
    floors = _floors()
    level = {n: i for i, names in enumerate(floors) for n in names}
    for name, targets in _arrows().items():
        for t in targets:
            a, b = (level.get(x.split(".")[1]) if "." in x else None for x in (name, t))
            if name.startswith("comparisons.bench"):
                continue  # the benchmarks may use any job
            assert t.startswith("comparisons.bench") <= name.startswith("comparisons.cli."), \
                f"{name} imports the benchmarks: only the command line's bench does"
            if a is None or b is None:
                continue
            assert b >= a, f"{name} imports {t}, which comparisons/__init__.py puts above it"


def test_the_import_graph_has_no_cycle():
    arrows = _arrows()
    state = {}

    def visit(v, path):
        state[v] = 1
        for w in arrows.get(v, ()):
            if state.get(w) == 1:
                pytest.fail("import cycle: " + " -> ".join(path[path.index(w):] + [w]))
            if w not in state:
                visit(w, path + [w])
        state[v] = 2

    for v in sorted(arrows):
        if v not in state:
            visit(v, [v])


def test_only_plots_import_matplotlib():
    for name, path in MODULES.items():
        if name.startswith("comparisons.plots"):
            continue
        assert not any(t.split(".")[0] == "matplotlib" for t in _imports(name, path)), name


def test_only_the_adapter_calls_the_roads():
    allowed = ("comparisons.roads", "comparisons.bench", "comparisons.peers")  # as stated
    for name, path in MODULES.items():
        if name.startswith(allowed):
            continue
        roads = {t.split(".")[0] for t in _imports(name, path)} & {"bem", "analytic"}
        assert not roads, f"{name} imports {roads}: the roads are called through roads.py"


@pytest.mark.parametrize("package", ["bem", "analytic", "comparisons", "viscosine"])
def test_no_package_imports_another_packages_private_modules(package):
    for path in (ROOT / package).rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and not node.level and node.module:
                names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            else:
                continue
            for name in names:
                top, _, rest = name.partition(".")
                if top in ("bem", "analytic", "comparisons", "viscosine") and top != package:
                    assert not any(p.startswith("_") for p in rest.split(".") if p), \
                        f"{path.relative_to(ROOT)} imports {name}, private to {top}"


# ---------------------------------------------------------- analytic: the road and the references
ANALYTIC = ROOT / "analytic"
REFERENCES = ANALYTIC / "references"
#: the paper's road: every module of analytic/ beside its front (__init__) and the references
ROAD = ("_accepted", "_closure", "_kernels", "_result", "dimensional", "full_contact", "hunter",
        "solver", "westergaard")
#: the independent references, each with the modules of analytic.references it may import
#: (the layer factor is plain elasticity the two solvers share; the road has no layer)
STANDALONE = {"fourier": {"_layer"}, "surface": {"_layer"}, "persson": set(), "_layer": set()}
#: what the front of analytic takes from the references: two long-standing public names
FRONT_NAMES = {"fourier_solve", "layer_factor"}


def _module_name(path):
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _analytic_imports(path):
    return {t for t in _imports(_module_name(path), path) if t}


def _in_references(target):
    return target == "analytic.references" or target.startswith("analytic.references.")


def test_every_module_of_analytic_is_the_road_or_a_reference():
    here = {p.stem for p in ANALYTIC.glob("*.py")} - {"__init__"}
    assert here == set(ROAD), "classify the new module: the paper's road or analytic/references"
    refs = {p.stem for p in REFERENCES.glob("*.py")} \
        | {p.name for p in REFERENCES.iterdir() if (p / "__init__.py").is_file()}
    assert refs - {"__init__"} == set(STANDALONE)


@pytest.mark.parametrize("path", sorted(REFERENCES.rglob("*.py")), ids=lambda p: _module_name(p))
def test_the_references_import_neither_bem_nor_the_road(path):
    for t in _analytic_imports(path):
        top = t.split(".")[0]
        assert top != "bem", f"{_module_name(path)} imports {t}: the references never use bem"
        if top == "analytic":
            assert _in_references(t), \
                f"{_module_name(path)} imports {t}: the paper's road is what the references judge"


@pytest.mark.parametrize("path", sorted(REFERENCES.rglob("*.py")), ids=lambda p: _module_name(p))
def test_each_reference_stands_alone(path):
    parts = _module_name(path).split(".")
    if len(parts) < 3:
        return  # the front of analytic.references: it re-exports its members' names
    allowed = STANDALONE[parts[2]] | {parts[2]}
    for t in _analytic_imports(path):
        if t.startswith("analytic.references."):
            assert t.split(".")[2] in allowed, f"{'.'.join(parts)} imports {t}"


@pytest.mark.parametrize("stem", ROAD)
def test_the_road_does_not_import_the_references(stem):
    for t in _analytic_imports(ANALYTIC / f"{stem}.py"):
        assert not _in_references(t), f"analytic.{stem} imports {t}"


def test_the_front_of_analytic_takes_only_the_public_names_from_the_references():
    taken = set()
    for t in _analytic_imports(ANALYTIC / "__init__.py"):
        if _in_references(t):
            taken.add(t)
    assert taken == {"analytic.references"} | {f"analytic.references.{n}" for n in FRONT_NAMES}


# ------------------------------------------------------------------------------ the operating point
#: a case's or spec's key whose default a module could write again (`.get("ratio", 3.0)`)
POINT_KEYS = ("ratio", "hk", "direction", "rtol", "field_points", "nodes")


def _literal_defaults(path):
    """(line, key) of every ``x.get("<point key>", <number>)`` in a module."""
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                and node.func.attr == "get" and len(node.args) == 2
                and isinstance(node.args[0], ast.Constant) and node.args[0].value in POINT_KEYS
                and isinstance(node.args[1], ast.Constant)
                and isinstance(node.args[1].value, (int, float))):
            yield node.lineno, node.args[0].value


def test_only_the_operating_point_writes_a_points_defaults():
    for name, path in MODULES.items():
        if name == "comparisons.operating_point":
            continue
        for line, key in _literal_defaults(path):
            pytest.fail(f"{name}:{line} writes the default of {key!r}: use "
                        "comparisons.operating_point (DEFAULTS, ratio_of, hk_of, direction_of)")
        text = path.read_text(encoding="utf-8")
        assert not re.search(r"^DEFAULTS\s*=", text, re.M), f"{name} defines DEFAULTS"


#: a keyword of the operating point whose default is DEFAULTS' (E∞/E0, hk, sliding direction)
SIGNATURE_KEYS = ("ratio", "hk", "direction")
#: the same word for something else: richardson's ratio is the refinement ratio of two meshes
NOT_A_POINT = {("comparisons.convergence", "richardson", "ratio")}


def _signature_defaults(name, path):
    """(line, function, keyword) of every numeric literal default of a `SIGNATURE_KEYS` keyword."""
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        a = node.args
        pos = a.posonlyargs + a.args
        pairs = list(zip(pos[len(pos) - len(a.defaults):], a.defaults))
        pairs += [(k, d) for k, d in zip(a.kwonlyargs, a.kw_defaults) if d is not None]
        for arg, d in pairs:
            if (arg.arg in SIGNATURE_KEYS and isinstance(d, ast.Constant)
                    and isinstance(d.value, (int, float)) and not isinstance(d.value, bool)
                    and (name, node.name, arg.arg) not in NOT_A_POINT):
                yield node.lineno, node.name, arg.arg


def test_no_signature_writes_a_points_default():
    """The peers and every job take E∞/E0, hk and the direction's defaults from
    comparisons.operating_point.DEFAULTS, not from a literal in a signature."""
    found = [f"{name}:{line} {func}({key}=...)" for name, path in MODULES.items()
             if name != "comparisons.operating_point"
             for line, func, key in _signature_defaults(name, path)]
    assert not found, f"literal point defaults in signatures: {found}"


def test_no_module_reads_an_error_text_back_into_an_option_name():
    # a refusal carries its parameter (viscosine.checks.Refusal); operating_point.named says it
    pattern = re.compile(r"re\.match\([^)]*is not allowed|split\(\": \", 1\)\[-1\]")
    for name, path in MODULES.items():
        assert not pattern.search(path.read_text(encoding="utf-8")), name


def test_the_operating_point_calls_no_road():
    assert not {"comparisons.roads", "comparisons.runner"} & _arrows()[
        "comparisons.operating_point"]

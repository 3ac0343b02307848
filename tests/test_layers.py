"""One-way layers (STYLE.md): a package imports only packages below it.

Order, bottom to top: errors, conventions < _core < geometry < design < machine < generation < meshing < rating <
manufacturing < io < viz < gearset < job < cli. The one exception: a result object's ``plot`` method may import
``viz`` lazily (the compute -> result -> ``.plot()`` pattern of python-control).
"""

import ast
from pathlib import Path

ORDER = ["errors", "conventions", "_core", "geometry", "design", "machine", "generation", "meshing", "rating",
         "manufacturing", "io", "viz", "gearset", "job", "cli"]
RANK = {name: i for i, name in enumerate(ORDER)}
RANK["conventions"] = RANK["errors"]  # both at the bottom, conventions may use errors and vice versa
ROOT = Path(__file__).resolve().parents[1] / "src" / "spiralbevel"


def _target(node, parts):
    if isinstance(node, ast.ImportFrom):
        if node.level:
            base = list(parts[:-1])[: len(parts) - node.level]
            full = base + (node.module.split(".") if node.module else [node.names[0].name])
            return full[0] if full else None
        if node.module and node.module.startswith("spiralbevel."):
            return node.module.split(".")[1]
    if isinstance(node, ast.Import):
        for a in node.names:
            if a.name.startswith("spiralbevel."):
                return a.name.split(".")[1]
    return None


def _imports(tree):
    """(node, name of the enclosing function or None) for every import."""
    out = []

    def visit(node, fn):
        for child in ast.iter_child_nodes(node):
            inner = child.name if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)) else fn
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                out.append((child, fn))
            visit(child, inner)

    visit(tree, None)
    return out


def test_layers_import_one_way():
    bad = []
    for f in ROOT.rglob("*.py"):
        parts = f.relative_to(ROOT).parts
        layer = parts[0] if len(parts) > 1 else f.stem
        if layer not in RANK:
            continue
        for node, fn in _imports(ast.parse(f.read_text(encoding="utf-8"))):
            t = _target(node, parts)
            if t is None or t == layer or t not in RANK:
                continue
            if RANK[t] < RANK[layer] or (t == "conventions" and layer == "errors"):
                continue
            if fn == "plot" and t == "viz":
                continue
            bad.append(f"{f.relative_to(ROOT)}:{node.lineno} imports {t} (layer {layer})")
    assert not bad, "\n".join(bad)

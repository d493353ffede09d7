"""Layout rules that ruff and import-linter do not check: no module imports another's private names."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("hairbrush_env", "controllers")


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _resolve(node: ast.ImportFrom, module: str, is_package: bool) -> str:
    if not node.level:
        return node.module or ""
    base = module.split(".") if is_package else module.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def private_imports() -> list[str]:
    """``file:line: target`` for each import of a private module or name from outside its owner."""
    bad = []
    files = [p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py")] + list(
        (ROOT / "scripts").glob("*.py")
    )
    for path in files:
        module = _module_name(path)
        tree = ast.parse(path.read_text(), filename=str(path))
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or node.module == "__future__":
                continue
            target = _resolve(node, module, path.name == "__init__.py")
            parts = target.split(".")
            # a private module (and its names) may be used by its own package (its siblings), not from outside it
            private_module = next((i for i, part in enumerate(parts) if part.startswith("_")), None)
            if private_module is not None:
                if not module.startswith(".".join(parts[:private_module]) + "."):
                    bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: {target}")
                continue
            for alias in node.names:
                if alias.name.startswith("_") and not alias.name.startswith("__") and target != module:
                    bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: {target}.{alias.name}")
    return bad


def test_no_module_imports_another_modules_private_names():
    assert private_imports() == []


def test_the_scan_finds_a_private_import(tmp_path, monkeypatch):
    """The rule above could pass by finding nothing at all: check it on a planted violation."""
    pkg = tmp_path / "controllers"
    pkg.mkdir()
    (pkg / "x.py").write_text("from hairbrush_env.topology._kernels import min_segment_distance\n")
    (pkg / "y.py").write_text("from hairbrush_env.scene import _FREE_CLEARANCE\n")
    monkeypatch.setitem(globals(), "ROOT", tmp_path)
    (tmp_path / "hairbrush_env").mkdir()
    (tmp_path / "scripts").mkdir()
    found = private_imports()
    assert len(found) == 2 and "topology._kernels" in found[0] + found[1]

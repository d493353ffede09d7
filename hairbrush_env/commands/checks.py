"""Input checks of the ``hairbrush`` command line, in one place.

Every check runs while the command line is parsed, before anything is simulated. The argparse *types* below raise
``argparse.ArgumentTypeError``, which argparse turns into one line naming the flag and its value
(``hairbrush rollout: error: argument --seed: must be an integer >= 0, got '-1'``) and exit code 2. Checks that need
more than one value, or a file's contents, run at the start of a handler and raise :class:`UsageError`, which
:func:`hairbrush_env.cli.main` prints the same way (exit code 2, no traceback).
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from pathlib import Path


class UsageError(ValueError):
    """A bad command-line input found by a handler before it simulates (printed as ``error: ...``, exit 2)."""

    def __init__(self, flag: str, message: str) -> None:
        super().__init__(f"argument {flag}: {message}")


def integer(minimum: int | None = None, maximum: int | None = None) -> Callable[[str], int]:
    """An int in ``[minimum, maximum]``."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None
        if minimum is not None and value < minimum:
            raise argparse.ArgumentTypeError(f"must be an integer >= {minimum}, got {text!r}")
        if maximum is not None and value > maximum:
            raise argparse.ArgumentTypeError(f"must be an integer <= {maximum}, got {text!r}")
        return value

    parse.__name__ = "integer"
    return parse


count = integer(1)  # episodes, strokes, frames, workers, ...
seed = integer(0)


def number(minimum: float | None = None, *, exclusive: bool = False, maximum: float | None = None):
    """A finite float above ``minimum`` (or at it, unless ``exclusive``) and at most ``maximum``."""

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"must be finite, got {text!r}")
        if minimum is not None and (value <= minimum if exclusive else value < minimum):
            raise argparse.ArgumentTypeError(
                f"must be {'>' if exclusive else '>='} {minimum:g}, got {text!r}"
            )
        if maximum is not None and value > maximum:
            raise argparse.ArgumentTypeError(f"must be <= {maximum:g}, got {text!r}")
        return value

    parse.__name__ = "number"
    return parse


positive = number(0.0, exclusive=True)
non_negative = number(0.0)


def number_list(item: Callable[[str], float] = positive) -> Callable[[str], list[float]]:
    """Comma-separated distinct numbers, each checked by ``item``."""

    def parse(text: str) -> list[float]:
        parts = [p.strip() for p in text.split(",") if p.strip()]
        if not parts:
            raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text!r}")
        values = [item(p) for p in parts]
        if len(set(values)) != len(values):  # each value is a cell of a grid (or a seed): twice is a typo
            raise argparse.ArgumentTypeError(f"values must not repeat, got {text!r}")
        return values

    return parse


def wig_choices() -> list[str]:
    """Every wig name the commands accept (presets, then the held-out wigs), for help texts."""
    from ..hair import HELD_OUT_WIGS, PRESETS

    return [*PRESETS, *HELD_OUT_WIGS]


def policy_choices() -> list[str]:
    """The registered policy names, for help texts."""
    from ..policies import available_policies

    return sorted(available_policies())


def wig_names(*, allow_all: bool = True, allow_held_out: bool = True) -> Callable[[str], list[str]]:
    """Comma-separated wig names (presets or held-out wigs); ``all`` → every preset, ``held_out`` → the held-out
    wigs. Unknown names are refused listing the valid ones."""

    def parse(text: str) -> list[str]:
        from ..hair import wig_names as resolve

        sets = [s for s, ok in (("all", allow_all), ("held_out", allow_held_out)) if ok]
        try:
            return resolve(text, sets=sets, held_out=allow_held_out)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None

    return parse


def wig_name(text: str) -> str:
    """One wig name."""
    names = wig_names(allow_all=False)(text)
    if len(names) != 1:
        raise argparse.ArgumentTypeError(f"expected one wig name, got {text!r}")
    return names[0]


def wig_field(text: str) -> tuple[str, object]:
    """``FIELD=VALUE``: a :class:`~hairbrush_env.hair.WigConfig` field and its value (JSON, e.g. ``root_run=1``),
    checked on the default preset so that an unknown field or a value out of its range fails before any simulation."""
    import dataclasses
    import json

    from ..hair import DEFAULT_WIG, PRESETS

    field, sep, raw = text.partition("=")
    if not sep or not field:
        raise argparse.ArgumentTypeError(f"expected FIELD=VALUE, got {text!r}")
    try:
        value = json.loads(raw)
    except json.JSONDecodeError:
        value = raw  # a bare string, e.g. name=mine
    known = {f.name for f in dataclasses.fields(PRESETS[DEFAULT_WIG])}
    if field not in known:
        raise argparse.ArgumentTypeError(
            f"unknown WigConfig field {field!r} (see hairbrush_env.hair.WigConfig)"
        )
    try:
        dataclasses.replace(PRESETS[DEFAULT_WIG], **{field: value})
    except (ValueError, TypeError) as exc:
        raise argparse.ArgumentTypeError(str(exc)) from exc
    return field, value


def policy_names(text: str) -> list[str]:
    """Comma-separated registered policy names (or ``sb3:DIR`` with an existing DIR)."""
    from ..policies import policy_entry_point

    names = [p.strip() for p in text.split(",") if p.strip()]
    if not names:
        raise argparse.ArgumentTypeError(f"expected comma-separated policy names, got {text!r}")
    for name in names:
        try:
            policy_entry_point(name)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc).removeprefix("policy: ")) from None
        if name.startswith("sb3:") and not Path(name[4:]).exists():
            raise argparse.ArgumentTypeError(f"no trained agent at {name[4:]!r} (policy {name!r})")
    return names


def policy_name(text: str) -> str:
    names = policy_names(text)
    if len(names) != 1:
        raise argparse.ArgumentTypeError(f"expected one policy, got {text!r}")
    return names[0]


def _writable_parent(path: Path) -> None:
    for parent in (path, *path.parents):
        if parent.exists():
            if parent != path and not parent.is_dir():
                raise argparse.ArgumentTypeError(f"{parent} is a file, so {path} cannot be created")
            return


def output_file(*suffixes: str) -> Callable[[str], str]:
    """A file to write, ending with one of ``suffixes``, whose directory can be created."""

    def parse(text: str) -> str:
        path = Path(text)
        if suffixes and path.suffix.lower() not in suffixes:
            raise argparse.ArgumentTypeError(f"expected a {' or '.join(suffixes)} file, got {text!r}")
        if path.is_dir():
            raise argparse.ArgumentTypeError(f"{text!r} is a directory")
        _writable_parent(path)
        return text

    parse.__name__ = "output file"
    return parse


def output_dir(text: str) -> str:
    """A directory to write into (created if missing): not an existing file, nor under one."""
    path = Path(text)
    if path.exists() and not path.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r} is a file, not a directory")
    _writable_parent(path)
    return text


def input_file(text: str) -> str:
    if not Path(text).is_file():
        raise argparse.ArgumentTypeError(f"no such file: {text!r}")
    return text


def ray_address(text: str) -> str:
    """``--ray``: ``auto`` or a cluster address; the optional ``ray`` extra must be installed."""
    from ..executor import cluster_address, ray_available

    text = text.strip()
    if text != "auto" and cluster_address(text) is None:
        raise argparse.ArgumentTypeError(f"expected 'auto' or HOST:PORT (or ray://HOST:PORT), got {text!r}")
    if not ray_available():
        raise argparse.ArgumentTypeError(
            f"{text!r} needs Ray, which is not installed: pip install 'hairbrush-env[ray]'"
        )
    return text

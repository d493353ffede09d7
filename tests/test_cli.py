"""The `hairbrush` command: help, version and the topology demo end to end."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from hairbrush_env import __version__
from hairbrush_env.cli import main


def test_help_and_version(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert __version__ in capsys.readouterr().out
    out = subprocess.run(
        [sys.executable, "-m", "hairbrush_env.cli", "--help"], capture_output=True, text=True
    )
    assert out.returncode == 0 and "topology" in out.stdout


def test_topology_demo_writes_outputs(tmp_path):
    assert main(["topology", "demo", "--out", str(tmp_path), "--frames", "6"]) == 0
    summary = json.loads((tmp_path / "topology_demo.json").read_text())
    lk = np.array(summary["lk"])
    assert lk[0] > 9 and abs(lk[-1]) < 1e-9  # all link expelled at the end of the stroke
    assert np.all(np.diff(lk) <= 1e-12)
    assert (tmp_path / "topology_demo.png").stat().st_size > 10_000
    assert (tmp_path / "topology_demo.rrd").stat().st_size > 1_000
    assert not list(tmp_path.glob(".*tmp*"))  # atomic writes leave no temporaries


def test_topology_lk_command(tmp_path, capsys):
    t = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    np.save(tmp_path / "a.npy", np.column_stack([np.cos(t), np.sin(t), 0 * t]))
    np.savetxt(tmp_path / "b.csv", np.column_stack([1 + np.cos(t), 0 * t, np.sin(t)]), delimiter=",")
    assert main(["topology", "lk", str(tmp_path / "a.npy"), str(tmp_path / "b.csv")]) == 0
    assert "Lk = -1.000000" in capsys.readouterr().out
    assert "warning" not in capsys.readouterr().err  # closed curves: no open-curve warning
    np.save(tmp_path / "arc.npy", np.column_stack([np.cos(t / 2), np.sin(t / 2), 0 * t]))  # half a circle
    assert main(["topology", "lk", str(tmp_path / "arc.npy"), str(tmp_path / "b.csv")]) == 0
    assert "curve_a looks open" in capsys.readouterr().err and "--open" not in " ".join(sys.argv)
    assert main(["topology", "lk", "--open", str(tmp_path / "arc.npy"), str(tmp_path / "b.csv")]) == 0
    assert "looks open" not in capsys.readouterr().err


def test_rodpile_summary_reports_the_bulk_away_from_the_wall(tmp_path, capsys):
    """`rodpile summary --plot`: container-averaged and bulk (≥ L/2 from the wall) φα, on a random gas of rods
    placed uniformly inside a 3 L cylinder. Near the wall a rod fits only as a steep rod or a chord, so the
    container average must be lower than the bulk value."""
    from hairbrush_env.studies.rod_pile import load_packing, packing_fraction

    length = 0.05
    path = tmp_path / "gas.npz"
    assert main(["rodpile", "gas", "--n-rods", "600", "--alpha", "20", "--container", "3", "--height", "2",
                 "--out", str(path)]) == 0  # fmt: skip
    pile = load_packing(path)
    assert main(["rodpile", "summary", str(path), "--out", str(tmp_path / "s.json"),
                 "--plot", str(tmp_path / "phi.png")]) == 0  # fmt: skip
    s = json.loads((tmp_path / "s.json").read_text())[0]
    assert s["phi_f_inner"] == pytest.approx(packing_fraction(pile, wall_margin=length / 2))
    assert s["phi_alpha_inner"] > 1.1 * s["phi_alpha"]
    assert np.isfinite(s["contacts_bulk_over_philipse_inner"])
    assert "≥ L/2 from the wall" in capsys.readouterr().out
    assert (tmp_path / "phi.png").stat().st_size > 10_000


def test_helix_run_and_sweep_commands(tmp_path, capsys):
    """``hairbrush helix run|sweep`` on a reduced helix: the printed summary (with break-throughs and kink jams),
    the files, the sweep's CSV columns, and clear errors for bad --set / --vary."""
    import csv

    reduced = [
        "--set",
        "height=0.06",
        "--set",
        "edges_per_pitch=8",
        "--set",
        "samples=40",
        "--set",
        "settle_time=0.2",
    ]
    assert main(["helix", "run", *reduced, "--out", str(tmp_path / "run")]) == 0
    out = capsys.readouterr().out
    assert "f_max = " in out and "kink jams" in out and "break-through at x = " in out  # at least the exit
    for name in ("combing.csv", "combing.json", "combing.png"):
        assert (tmp_path / "run" / name).stat().st_size > 0
    summary = json.loads((tmp_path / "run" / "combing.json").read_text())
    assert summary["kink_jams"] == 0 and summary["kink_free_drops"] >= 0

    sweep = [
        "helix",
        "sweep",
        "--vary",
        "P_over_r=18,48",
        *reduced,
        "--workers",
        "1",
        "--out",
        str(tmp_path / "sw"),
    ]
    assert main(sweep) == 0
    rows = list(csv.DictReader((tmp_path / "sw" / "sweep_P_over_r.csv").open()))
    assert [float(r["value"]) for r in rows] == [18.0, 48.0]
    assert float(rows[0]["f_max"]) > float(rows[1]["f_max"])  # claim 1 through the command
    assert {"kink_jams", "kink_free_drops", "bend_max_deg", "jammed"} <= set(rows[0])
    assert (tmp_path / "sw" / "sweep_P_over_r.png").stat().st_size > 10_000
    assert "kink jams" in capsys.readouterr().out

    assert "P_over_r" in refused(
        ["helix", "run", "--set", "P_over_r=-1", "--out", str(tmp_path / "bad")], capsys
    )
    assert "NAME=v1" in refused(
        ["helix", "sweep", "--vary", "P_over_r", "--out", str(tmp_path / "bad")], capsys
    )


def refused(argv: list[str], capsys) -> str:
    """Run ``hairbrush ARGV``; assert it was refused as a usage error (exit code 2, no traceback); its stderr."""
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse's own errors
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2, (argv, code, err)
    assert "Traceback" not in err and len(err.strip().splitlines()[-1]) < 400
    return err.strip().splitlines()[-1]


@pytest.fixture(scope="module")
def bad_files(tmp_path_factory):
    d = tmp_path_factory.mktemp("bad")
    (d / "a_file").write_text("not a directory\n")
    (d / "malformed.csv").write_text("1,2\n3,oops,4\n")
    t = np.linspace(0, 2 * np.pi, 20, endpoint=False)
    np.savetxt(d / "ring.csv", np.column_stack([np.cos(t), np.sin(t), 0 * t]), delimiter=",")
    assert main(["rodpile", "gas", "--n-rods", "5", "--out", str(d / "tiny.npz")]) == 0
    return d


# (argv with {d} for the directory of bad_files, text the error line must contain: the flag and the value)
BAD_INPUT = [
    (["rollout", "--seed", "-1"], ["--seed", "-1"]),
    (["rollout", "--wig-seed", "-2"], ["--wig-seed", "-2"]),
    (["rollout", "--max-steps", "0"], ["--max-steps", "'0'"]),
    (["rollout", "--max-steps", "-3"], ["--max-steps", "-3"]),
    (["rollout", "--episodes", "0"], ["--episodes", "'0'"]),
    (["rollout", "--wig", "bogus"], ["--wig", "bogus", "curly"]),
    (["rollout", "--policy", "bogus"], ["--policy", "bogus", "sigmoid"]),
    (["rollout", "--json", "{d}/a_file/out.json"], ["--json", "a_file"]),
    (["rollout", "--plot", "out.txt"], ["--plot", "out.txt"]),
    (["rollout", "--width", "5"], ["--width", "'5'"]),
    (["rollout", "--set", "root_run=2"], ["--set", "root_run", "2"]),
    (["rollout", "--set", "bogus=1"], ["--set", "bogus"]),
    (["rollout", "--set", "root_run"], ["--set", "root_run"]),
    (["compare", "--policies", "full,bogus"], ["--policies", "bogus"]),
    (["compare", "--wigs", "curly,nope"], ["--wigs", "nope"]),
    (["compare", "--out", "{d}/a_file"], ["--out", "a_file"]),
    (["compare", "--workers", "0"], ["--workers", "'0'"]),
    (["strokes", "--brush-lengths", "0.5,1.5"], ["--brush-lengths", "1.5"]),
    (["strokes", "--speeds", "0.1,-1"], ["--speeds", "-1"]),
    (["repeat", "--brush-length", "0"], ["--brush-length", "'0'"]),
    (["repeat", "--strokes", "0"], ["--strokes", "'0'"]),
    (["repeat", "--physics", "v11"], ["--physics", "'v11'"]),
    (["compare", "--physics", "v1.5"], ["--physics", "'v1.5'"]),
    (["rollout", "--env", "HairBrush-v11"], ["--env", "'HairBrush-v11'"]),
    (["topology", "demo", "--frames", "-3"], ["--frames", "-3"]),
    (["topology", "lk", "{d}/malformed.csv", "{d}/ring.csv"], ["curve_a", "malformed.csv"]),
    (["topology", "lk", "{d}/ring.csv", "{d}/missing.csv"], ["curve_b", "missing.csv"]),
    (["census", "--seeds", "-1"], ["--seeds", "-1"]),
    (["census", "--hairs", "1"], ["--hairs", "'1'"]),
    (["helix", "run", "--set", "nonsense"], ["--set", "nonsense"]),
    (["helix", "sweep", "--vary", "P_over_r"], ["--vary", "P_over_r"]),
    (["rodpile", "generate", "--n-rods", "0"], ["--n-rods", "'0'"]),
    (["rodpile", "fields", "{d}/tiny.npz", "--ls", "1000", "--out", "{d}/fields"], ["--ls", "1000"]),
    (["rodpile", "fields", "{d}/missing.npz"], ["piles", "missing.npz"]),
    (["rodpile", "segment", "{d}/ring.csv", "--diameter", "-1"], ["--diameter", "-1"]),
    (["vision", "calibrate", "--seeds", "-1"], ["--seeds", "-1"]),
]


@pytest.mark.parametrize(("argv", "expected"), BAD_INPUT, ids=[" ".join(a) for a, _ in BAD_INPUT])
def test_bad_input_is_refused_before_anything_runs(argv, expected, bad_files, capsys):
    """One line naming the flag and its value, exit code 2, no traceback, nothing simulated (issue 23's table)."""
    line = refused([a.replace("{d}", str(bad_files)) for a in argv], capsys)
    for text in expected:
        assert text in line, (text, line)
    assert not (bad_files / "fields" / "fields.json").exists()


def test_help_lists_wigs_and_policies_and_every_option_has_help():
    """``--help`` names the wig presets and registered policies; every option of every command has a help text."""
    import argparse

    from hairbrush_env.cli import build_parser
    from hairbrush_env.hair import PRESETS
    from hairbrush_env.policies import available_policies

    parser = build_parser()

    def walk(p: argparse.ArgumentParser, path: str):
        for action in p._actions:
            if isinstance(action, argparse._SubParsersAction):
                for name, child in action.choices.items():
                    yield from walk(child, f"{path} {name}")
            elif not isinstance(action, argparse._HelpAction):
                yield path, action

    missing = [
        f"{path} {'/'.join(a.option_strings) or a.dest}"
        for path, a in walk(parser, "hairbrush")
        if not a.help
    ]
    assert missing == []
    rollout = subprocess.run(
        [sys.executable, "-m", "hairbrush_env.cli", "rollout", "--help"], capture_output=True, text=True
    ).stdout
    flat = " ".join(rollout.split())
    assert all(w in flat for w in PRESETS) and all(p in flat for p in available_policies())
    assert "(default: curly)" in flat and "(default: 0)" in flat


def test_rollout_set_changes_a_wig_field_on_top_of_the_versions(monkeypatch):
    """``hairbrush rollout --set root_run=1`` hands the env its version's wig fields with that one changed (an env's
    ``wig_fields`` replace the version's, so passing the field alone would drop v10's others)."""
    import hairbrush_env.envs as envs
    from hairbrush_env.physics import get_physics

    seen = {}

    def fake_make(env_id, **kwargs):
        seen.update(kwargs, env_id=env_id)
        raise ValueError("stop before building the scene")

    monkeypatch.setattr(envs, "make_version", fake_make)
    with pytest.raises(SystemExit, match="stop before building"):
        main(
            [
                "rollout",
                "--env",
                "HairBrush-v10",
                "--wig",
                "coily",
                "--set",
                "root_run=1",
                "--set",
                "damping=0.5",
            ]
        )
    assert seen["env_id"] == "HairBrush-v10"
    assert seen["wig_fields"] == {**get_physics("v10").wig_fields, "root_run": 1, "damping": 0.5}

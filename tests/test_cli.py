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
    with pytest.raises(SystemExit, match="not found"):
        main(["topology", "lk", str(tmp_path / "missing.npy"), str(tmp_path / "b.csv")])


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

    with pytest.raises(SystemExit, match="P_over_r"):
        main(["helix", "run", "--set", "P_over_r=-1", "--out", str(tmp_path / "bad")])
    with pytest.raises(SystemExit, match="--vary expects"):
        main(["helix", "sweep", "--vary", "P_over_r", "--out", str(tmp_path / "bad")])

"""Issue 13: the one progress bar (:mod:`gearkit.progress`) -- on stderr only when stderr is a
terminal (a real pseudo-terminal here) or with ``--progress``; never on stdout, never in the JSON, never
to a pipe unless asked; it ends with a newline; nothing is drawn or timed when it is off.

A bar waits :attr:`Progress.delay` seconds of work before it appears (quick runs stay quiet); the
tests set it to 0 so that a short run shows its bar.
"""
import io
import json
import os
import pty
import select
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gearkit.cli import main
from gearkit.progress import Progress

#: runs the CLI with the bar's delay at 0 in a fresh process: argv as JSON in argv[1]
CHILD = ("import json, sys; from gearkit.progress import Progress; Progress.delay = 0.0; "
         "from gearkit.cli import main; sys.exit(main(json.loads(sys.argv[1])))")
BLOCKING = ["blocking", "--z1", "13", "--z2", "16", "--tol", "1e-3", "--json"]


def _env():
    return dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))


def _run_on_a_terminal(argv, tmp_path):
    """Run the CLI with stderr on a pseudo-terminal and stdout to a file: (code, stdout, terminal text)."""
    leader, follower = pty.openpty()
    try:
        with open(tmp_path / "stdout", "wb") as sink:
            proc = subprocess.Popen([sys.executable, "-c", CHILD, json.dumps(argv)], stdout=sink,
                                    stderr=follower, stdin=subprocess.DEVNULL, env=_env())
        os.close(follower)
        seen = b""
        while True:
            ready, _, _ = select.select([leader], [], [], 120)
            if not ready:
                proc.kill()
                raise AssertionError("no end of output from the child within 120 s")
            try:
                chunk = os.read(leader, 65536)
            except OSError:  # the child closed the terminal (EIO on Linux)
                break
            if not chunk:
                break
            seen += chunk
        proc.wait(timeout=120)
    finally:
        os.close(leader)
    return proc.returncode, (tmp_path / "stdout").read_text(), seen.decode()


def _run_piped(argv):
    proc = subprocess.run([sys.executable, "-c", CHILD, json.dumps(argv)], capture_output=True, text=True,
                          env=_env(), timeout=300)
    return proc.returncode, proc.stdout, proc.stderr


def test_a_bar_on_a_terminal_ends_with_a_newline_and_stdout_stays_json(tmp_path):
    code, out, term = _run_on_a_terminal(BLOCKING, tmp_path)
    assert code in (0, 1), term
    assert "blocking [" in term and "4/4 stages" in term
    assert term.endswith("\n")  # the last bar line is finished (a terminal shows "\r\n")
    assert term.count("\n") == 1 and term.count("\r") >= 2  # redrawn in place on one line
    assert "blocking [" not in out
    json.loads(out)  # stdout is the one JSON object, untouched


def test_no_bar_to_a_pipe_unless_asked():
    code, out, err = _run_piped(BLOCKING)
    assert code in (0, 1) and "[" not in err and err == ""
    json.loads(out)
    code, out, err = _run_piped(["--progress", *BLOCKING])
    assert code in (0, 1)
    assert "blocking [##############################] 4/4 stages" in err and err.endswith("\n")
    json.loads(out)


def test_the_atlas_draws_no_bar_to_a_pipe_unless_asked(tmp_path):
    """The atlas follows the one rule too (it used to force its bar on whatever stderr was)."""
    argv = ["atlas", "--z1", "13", "--z2", "16", "--tol", "1e-2", "--workers", "1", "--json"]
    code, out, err = _run_piped(argv + ["-o", str(tmp_path / "a")])
    assert code in (0, 1) and "atlas [" not in err
    json.loads(out)
    code, out, err = _run_piped(["--progress", *argv, "-o", str(tmp_path / "b")])
    assert code in (0, 1) and "atlas [" in err and err.endswith("\n")


def test_progress_is_a_shared_flag_anywhere_on_the_line(capsys, monkeypatch):
    monkeypatch.setattr(Progress, "delay", 0.0)
    argv = ["pair", "--z1", "20", "--z2", "40", "-m", "2", "--width", "5", "--sweep", "3", "--json"]
    assert main(argv + ["--progress"]) == 0
    out, err = capsys.readouterr()
    assert "sweep [##############################] 3/3 rotations" in err and err.endswith("\n")
    assert "sweep" in json.loads(out)
    assert main(argv) == 0  # the pytest capture is no terminal: no bar
    assert "sweep [" not in capsys.readouterr().err
    assert Progress.mode == "off"  # the command line puts the library default back


def test_contact_steps_draw_a_bar(capsys, monkeypatch):
    monkeypatch.setattr(Progress, "delay", 0.0)
    assert main(["--progress", "contact", "--z1", "20", "--z2", "40", "-m", "2", "--steps", "64", "--json"]) in (0, 1)
    out, err = capsys.readouterr()
    assert "contact [" in err and "positions" in err
    json.loads(out)


def test_off_costs_one_attribute_test_per_step(monkeypatch):
    """Off (the library default), ``update`` neither reads the clock nor writes."""
    import gearkit.progress

    stream = io.StringIO()
    with Progress("x", 10, stream=stream) as bar:
        monkeypatch.setattr(gearkit.progress.time, "monotonic", lambda: pytest.fail("the clock was read"))
        for k in range(10):
            bar.update(k + 1)
    assert bar.enabled is False and bar.done == 10 and stream.getvalue() == ""


def test_delay_throttle_nesting_and_interrupt():
    stream = io.StringIO()
    with Progress("quick", 5, enabled=True, stream=stream, delay=60.0) as bar:
        bar.update(5)
    assert stream.getvalue() == ""  # finished before the delay: never drawn
    with Progress("outer", 2, enabled=True, stream=stream, delay=0.0) as outer:
        with Progress("inner", 2, enabled=True, stream=stream, delay=0.0) as inner:
            inner.update(2)
        outer.update(1)
        outer.update(2)  # within the redraw interval: not drawn until the end
    text = stream.getvalue()
    assert inner.enabled is False and "inner" not in text
    assert text.count("\r") == 2 and text.count("\n") == 1  # drawn at 1/2, then the last state at the end
    assert text.rstrip("\n").rsplit("\r", 1)[-1].startswith("outer [##############################] 100%")
    stream = io.StringIO()
    with pytest.raises(KeyboardInterrupt):
        with Progress("cut", 4, enabled=True, stream=stream, delay=0.0) as bar:
            bar.update(1)
            raise KeyboardInterrupt
    assert stream.getvalue().endswith("\n") and "1/4" not in stream.getvalue() and " 25%" in stream.getvalue()
    assert Progress._depth == 0


def test_a_bar_inside_a_drawn_one_moves_it_within_its_step(monkeypatch):
    monkeypatch.setattr(Progress, "interval", 0.0)  # every update draws
    stream = io.StringIO()
    with Progress("scene", 2, unit="meshes", enabled=True, stream=stream, delay=0.0) as outer:
        outer.update(0)
        with Progress("contact", 4, unit="positions", enabled=True, stream=stream, delay=0.0) as inner:
            for k in range(4):
                inner.update(k + 1)
        outer.update(1)
    frames = stream.getvalue().replace("\n", "").split("\r")[1:]
    assert inner.enabled is False and not any(f.startswith("contact") for f in frames)
    # each step of the inner bar is an eighth of the outer bar (a quarter of its first half)
    bars = [f.split("[", 1)[1].split("]", 1)[0].count("#") for f in frames]
    assert bars[:5] == [int(Progress.width * k / 8) for k in range(5)]
    assert [f.split("] ", 1)[1].split(",")[0] for f in frames[:5]] == ["0/2 meshes"] * 5
    assert frames[-1].startswith("scene [" + "#" * Progress.width + "] 2/2 meshes")


def test_a_long_export_draws_its_bar_only_where_asked(tmp_path):
    """Every mesh and profile writer advances a bar by what it has written: with ``--progress`` the
    bar of a binary STL ends at the facet count the file's header states; to a pipe without it, nothing."""
    stl = tmp_path / "g.stl"
    argv = ["gear", "-z", "40", "-m", "2", "--width", "5", "--tol", "1e-3", "-o", str(stl)]
    code, out, err = _run_piped(argv)
    assert code == 0 and "[" not in err
    code, out, err = _run_piped(["--progress", *argv])
    facets = int(np.frombuffer(stl.read_bytes()[80:84], "<u4")[0])
    assert code == 0 and f"STL [{'#' * Progress.width}] {facets}/{facets} facets" in err
    assert "mesh check [" in err and err.rstrip("\n").rsplit("\n", 1)[-1].startswith("gearkit gear: wrote")
    for suffix in ("obj", "glb", "3mf"):
        code, out, err = _run_piped(["--progress", *argv[:-1], str(tmp_path / f"g.{suffix}")])
        assert code == 0 and f"{suffix.upper()} [{'#' * Progress.width}]" in err
    for suffix in ("dxf", "svg", "csv", "json"):
        code, out, err = _run_piped(["--progress", "rack", "-m", "2", "-n", "400", "-o", str(tmp_path / f"r.{suffix}")])
        assert code == 0 and f"{suffix.upper()} [{'#' * Progress.width}]" in err


def test_a_rack_bar_draws_on_a_terminal(tmp_path):
    code, out, term = _run_on_a_terminal(["rack", "-m", "1", "-n", "30", "-o", str(tmp_path / "r.stl")], tmp_path)
    assert code == 0, term
    assert "rack bar [" in term and "2/2 stages" in term and "STL [" in term
    assert "rack bar [" not in out


def test_scene_and_planetary_queries_draw_bars_when_asked(tmp_path):
    scene = str(Path(__file__).resolve().parent.parent / "examples" / "planetary.toml")
    code, out, err = _run_piped(["--progress", "scene", scene, "--fidelity", "simulated", "--json"])
    meshes = len(json.loads(out)["meshes"])
    assert code in (0, 1) and f"scene [{'#' * Progress.width}] {meshes}/{meshes} meshes" in err
    assert "contact [" not in err  # the contact of each mesh moves the scene's bar instead
    code, out, err = _run_piped(["scene", scene, "--fidelity", "simulated", "--json"])
    assert code in (0, 1) and err == ""
    argv = ["planetary", "--ratio", "5", "--planets", "3", "-m", "1", "--max-teeth", "80", "--ratio-tol", "0.01", "--json"]
    code, out, err = _run_piped(["--progress", *argv])
    assert code == 0 and "planetary search [" in err and "planetary checks [" in err
    assert _run_piped(argv)[2] == ""

"""Issue 13, each row a test: no traceback ever, nothing left at the destination, bounded work.

Every case runs the CLI in-process (``gearkit.cli.main``) and reads its exit status and stderr:
exit 2 with one line naming the file or field for bad input and file problems, 130/143 for an
interrupt, 70 with a ``--debug`` hint for an internal error.
"""
import json
import os
import signal
import subprocess
import sys

import pytest

from gearkit.cli import COMMANDS, build_parser, main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert "Traceback" not in err and "Traceback" not in out
    return code, out, err


def one_error_line(err: str) -> str:
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    return lines[0]


def leftovers(folder):
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".part") or p.name.startswith(".gearkit-"))


@pytest.mark.parametrize("argv", [
    ["gear", "-z", "20", "-m", "2", "-o", "{d}.svg"],
    ["gear", "-z", "20", "-m", "2", "--width", "5", "-o", "{d}.stl"],
    ["blocking", "--z1", "13", "--z2", "16", "-o", "{d}.png"],
    ["pair", "--z1", "20", "--z2", "40", "-m", "2", "--width", "5", "-o", "{d}.stl"],
    ["bench", "--quick", "-o", "{d}.json"],
])
def test_output_onto_a_directory_is_refused_before_any_work(capsys, tmp_path, argv, monkeypatch):
    import gearkit.bench

    monkeypatch.setattr(gearkit.bench, "run_bench", lambda **kw: pytest.fail("the bench ran"))
    target = tmp_path / ("out" + argv[-1][3:])
    target.mkdir()
    code, _, err = run(capsys, *[a.replace("{d}", str(tmp_path / "out")) for a in argv])
    assert code == 2
    assert "is a directory" in one_error_line(err) and "-o" in err
    assert list(target.iterdir()) == [] and leftovers(tmp_path) == []


@pytest.mark.parametrize("argv", [
    ["blocking", "--z1", "13", "--z2", "16", "-o", "/nonexistent-gk/c.png"],
    ["contact", "--z1", "20", "--z2", "40", "-m", "2", "-o", "/nonexistent-gk/te.png"],
    ["bench", "--quick", "-o", "/nonexistent-gk/b.json"],
    ["gear", "-z", "20", "-m", "2", "-o", "/nonexistent-gk/g.svg"],
])
def test_output_into_a_missing_directory_is_refused_before_any_work(capsys, argv, monkeypatch):
    import gearkit.bench

    monkeypatch.setattr(gearkit.bench, "run_bench", lambda **kw: pytest.fail("the bench ran"))
    code, _, err = run(capsys, *argv)
    assert code == 2 and "'/nonexistent-gk' does not exist" in one_error_line(err)


def test_every_output_flag_of_every_command_is_checked(tmp_path, monkeypatch):
    """An unwritable folder is refused for every registered command's output flags (by construction)."""
    import gearkit.export
    from gearkit.cli.shell import OUTPUT_DESTS, check_outputs
    from gearkit.errors import SpecError

    locked = tmp_path / "locked"
    locked.mkdir()
    real = os.access
    monkeypatch.setattr(gearkit.export.os, "access", lambda p, mode: False if str(p) == str(locked) else real(p, mode))
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    checked = 0
    for name in COMMANDS:
        for action in sub.choices[name]._actions:
            if action.dest in OUTPUT_DESTS:
                ns = type("A", (), {})()
                value = str(locked / "f.png")
                setattr(ns, action.dest, [value] if isinstance(action.default, list) else value)
                with pytest.raises(SpecError, match="is not writable"):
                    check_outputs(ns)
                checked += 1
    assert checked >= 10  # every command that writes a file has -o (and cam --plot)


def test_unwritable_directory_end_to_end(capsys, tmp_path, monkeypatch):
    import gearkit.export

    real = os.access
    monkeypatch.setattr(gearkit.export.os, "access", lambda p, mode: False if str(p) == str(tmp_path) else real(p, mode))
    code, _, err = run(capsys, "gear", "-z", "20", "-m", "2", "-o", str(tmp_path / "g.svg"))
    assert code == 2 and "is not writable" in one_error_line(err)
    assert list(tmp_path.iterdir()) == []


#: a command line of every command that writes, without its output (which the test appends)
WRITERS = [
    ["demo", "--out-dir"], ["gear", "-z", "20", "-m", "2", "-o"], ["rack", "-m", "2", "-o"],
    ["pair", "--z1", "20", "--z2", "40", "-m", "2", "-o"], ["bench", "--quick", "-o"],
    ["novikov", "--z1", "20", "--z2", "40", "-m", "2", "-o"], ["blocking", "--z1", "13", "--z2", "16", "-o"],
    ["atlas", "--z1", "12", "--z2", "30", "-o"],
    ["cycloidal-drive", "--pins", "12", "--lobes", "11", "--pin-circle-radius", "40", "--pin-radius", "3",
     "--eccentricity", "1.5", "-o"],
    ["cycloid", "-m", "2", "--pinion-teeth", "10", "--wheel-teeth", "40", "-o"],
    ["contact", "--z1", "20", "--z2", "40", "-m", "2", "-o"], ["view", "pair", "--z1", "20", "--z2", "40", "-m", "2", "-o"],
    ["cam", "-o"], ["cam", "--plot"], ["scene", "{scene}", "-o"],
]
SUFFIX = {"demo": "", "atlas": "", "bench": ".json", "contact": ".png", "blocking": ".png", "view": ".html",
          "cam": ".svg", "scene": ".html"}


@pytest.mark.skipif(not os.path.isdir("/sys/kernel"), reason="needs Linux's /sys (not writable, even by root)")
@pytest.mark.parametrize("argv", WRITERS, ids=[" ".join(w[:1] + w[-1:]) for w in WRITERS])
def test_unwritable_directory_for_every_command_even_as_root(capsys, tmp_path, monkeypatch, argv):
    """A folder nobody can write in (``/sys``: root too; permission bits do not stop root) is refused
    for every command's output before any work."""
    import gearkit.cli

    real_parse = gearkit.cli.parse_command_line

    def parse_without_work(argv):
        ns = real_parse(argv)
        ns.run = lambda args: pytest.fail("the command ran")
        return ns

    monkeypatch.setattr(gearkit.cli, "parse_command_line", parse_without_work)
    scene = tmp_path / "s.toml"
    scene.write_text("")
    target = "/sys/gearkit-test-out" + SUFFIX.get(argv[0], ".svg")
    code, _, err = run(capsys, *[a.replace("{scene}", str(scene)) for a in argv], target)
    assert code == 2 and "'/sys' is not writable" in one_error_line(err), err
    assert not os.path.exists(target)


def test_every_writing_command_is_in_the_unwritable_table():
    """The table above lists every output flag of every command (and of view's subcommands)."""
    import argparse

    from gearkit.cli.shell import OUTPUT_DESTS, OUTPUT_DIR_DESTS

    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    flags = set()
    for name, sp in sub.choices.items():
        nested = [a for a in sp._actions if isinstance(a, argparse._SubParsersAction)]
        parsers = [(name, sp)] + [(f"{name} {n}", p) for a in nested for n, p in a.choices.items()]
        for label, p in parsers:
            for action in p._actions:
                if action.dest in OUTPUT_DESTS + OUTPUT_DIR_DESTS:
                    flags.add((label.split()[0], action.option_strings[0]))
    covered = {(w[0], w[-1]) for w in WRITERS}
    assert flags - covered == set()


def test_os_error_while_writing_is_one_line_exit_2(capsys, tmp_path, monkeypatch):
    """A file problem found only while writing (permission, disk full) is one line, exit 2."""
    import gearkit.export

    real = os.open

    def denied(path, *a, **k):
        if str(path).startswith(str(tmp_path)):  # creating the temporary file in the target folder
            raise PermissionError(13, "Permission denied", str(path))
        return real(path, *a, **k)

    monkeypatch.setattr(gearkit.export.os, "open", denied)
    code, _, err = run(capsys, "gear", "-z", "20", "-m", "2", "-o", str(tmp_path / "g.svg"))
    assert code == 2 and "Permission denied" in one_error_line(err)


def test_demo_out_dir_onto_a_file(capsys, tmp_path):
    f = tmp_path / "afile"
    f.write_text("keep")
    code, _, err = run(capsys, "demo", "--out-dir", str(f))
    assert code == 2 and "is a file, not a directory" in one_error_line(err)
    assert f.read_text() == "keep"


@pytest.mark.parametrize("content", [b"\xff\xfe\x00\x01binary", "z1 = 'é'".encode("latin-1")])
def test_binary_or_non_utf8_toml(capsys, tmp_path, content):
    f = tmp_path / "file.toml"
    f.write_bytes(content)
    code, _, err = run(capsys, "check", str(f))
    assert code == 2 and "file.toml" in one_error_line(err) and "UTF-8" in err


def test_large_shift_on_a_huge_gear_is_no_traceback(capsys):
    code, out, err = run(capsys, "gear", "-z", "997", "-m", "25", "-x", "3", "--json")
    assert code in (0, 2)
    if code == 0:
        assert json.loads(out)["teeth"] == 997
    else:
        one_error_line(err)


def _interrupt_while_writing(monkeypatch, raiser):
    """Make the SVG writer write half a file, then be interrupted."""
    import gearkit.export

    real = gearkit.export._svg

    def half(loops, tmp):
        real(loops, tmp)
        raiser()

    monkeypatch.setattr(gearkit.export, "_svg", half)


def test_ctrl_c_during_an_export_exits_130_and_leaves_nothing(capsys, tmp_path, monkeypatch):
    def ctrl_c():
        raise KeyboardInterrupt

    _interrupt_while_writing(monkeypatch, ctrl_c)
    code, _, err = run(capsys, "gear", "-z", "20", "-m", "2", "-o", str(tmp_path / "g.svg"))
    assert code == 130 and one_error_line(err) == "gearkit gear: interrupted"
    assert list(tmp_path.iterdir()) == []


def test_ctrl_c_after_a_progress_bar_on_a_pipe_leaves_no_blank_line(capsys, tmp_path, monkeypatch):
    """The bar ends its own line when interrupted; the message follows at once (a pipe has no ``^C`` echo to
    step over, so a second line break would be an empty line in the log)."""
    from gearkit.progress import Progress

    def bar_then_ctrl_c():
        with Progress("export", 4, delay=0.0) as bar:
            bar.update(1)
            raise KeyboardInterrupt

    _interrupt_while_writing(monkeypatch, bar_then_ctrl_c)
    code, _, err = run(capsys, "--progress", "gear", "-z", "20", "-m", "2", "-o", str(tmp_path / "g.svg"))
    lines = err.split("\n")
    assert code == 130 and lines[0].startswith("\rexport [") and lines[1:] == ["gearkit gear: interrupted", ""]
    assert list(tmp_path.iterdir()) == []


def test_a_terminal_gets_the_line_break_that_steps_over_the_echoed_ctrl_c():
    """On a terminal the ``^C`` echo holds the line: the message starts a new one, unless a bar just did."""
    import io

    from gearkit.progress import Progress, line_break

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    tty = Terminal()
    assert line_break(tty) == "\n" and line_break(io.StringIO()) == ""
    try:
        with Progress("work", 2, enabled=True, stream=tty, delay=0.0) as bar:
            bar.update(1)
            raise KeyboardInterrupt
    except KeyboardInterrupt:
        pass
    assert tty.getvalue().endswith("\n") and line_break(tty) == ""


def test_sigterm_during_an_export_exits_143_and_leaves_nothing(capsys, tmp_path, monkeypatch):
    _interrupt_while_writing(monkeypatch, lambda: os.kill(os.getpid(), signal.SIGTERM))
    before = signal.getsignal(signal.SIGTERM)
    code, _, err = run(capsys, "gear", "-z", "20", "-m", "2", "-o", str(tmp_path / "g.svg"))
    assert code == 143 and one_error_line(err) == "gearkit gear: terminated"
    assert list(tmp_path.iterdir()) == []
    assert signal.getsignal(signal.SIGTERM) is before  # the handler is put back


def _signals_at_default():
    """In the child before it runs: SIGINT and SIGTERM at their defaults. A suite started as a background
    job inherits SIGINT ignored, and Python (rightly) leaves an inherited ignore in place, so the child
    would never see the signal this test sends."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


@pytest.mark.parametrize("sig, code, word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")])
def test_a_real_signal_during_a_long_export_leaves_no_part_file(tmp_path, sig, code, word):
    """A real process, signalled while its ``.part`` file is being written (a z = 2000 DXF at tol 1e-5
    is about 19 MB, so its writing lasts long enough to be caught on a loaded machine): the exit
    status is 130/143, one line, and the folder is left empty.

    On a loaded machine the signal can arrive after the file was renamed into place; such an
    attempt must have finished cleanly (exit 0, the whole file, no ``.part``) and is repeated, so
    that at least one attempt is really interrupted mid-write."""
    import time

    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    out = tmp_path / "g.dxf"
    for _attempt in range(5):
        proc = subprocess.Popen([sys.executable, "-m", "gearkit", "gear", "-z", "2000", "-m", "1", "--tol", "1e-5",
                                 "-o", str(out)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env,
                                preexec_fn=_signals_at_default)
        deadline = time.monotonic() + 300
        while not [p for p in leftovers(tmp_path) if p.startswith(".g.dxf.")]:
            assert proc.poll() is None, "the export ended before its .part file was seen"
            assert time.monotonic() < deadline, "no .part file within 300 s"
            time.sleep(0.002)
        proc.send_signal(sig)
        err = proc.communicate(timeout=300)[1]
        assert "Traceback" not in err
        if proc.returncode == 0:  # the signal came after the rename: a whole file, nothing left over
            assert leftovers(tmp_path) == [] and out.read_text(encoding="utf-8").rstrip().endswith("EOF")
            out.unlink()
            continue
        assert proc.returncode == code
        assert one_error_line(err) == f"gearkit gear: {word}"
        assert list(tmp_path.iterdir()) == []
        return
    pytest.fail("five exports finished before the signal reached them")


def test_ctrl_c_while_an_error_is_reported_exits_130(capsys, tmp_path, monkeypatch):
    """Found by the long CLI fuzz: an interrupt landing in the shell's own clean-up (after the
    command's error) escaped main. It is one line and 130 too."""
    import gearkit.cli.shell

    real, calls = gearkit.cli.shell._signal.signal, []

    def signal_then_interrupt(*a):
        calls.append(a)
        if len(calls) == 2:  # the handler being put back, in run_guarded's finally
            raise KeyboardInterrupt
        return real(*a)

    before = signal.getsignal(signal.SIGTERM)
    monkeypatch.setattr(gearkit.cli.shell._signal, "signal", signal_then_interrupt)
    try:
        code, _, err = run(capsys, "gear", "-z", "20", "-m", "2", "-o", str(tmp_path / "missing" / "g.svg"))
    finally:
        monkeypatch.undo()
        signal.signal(signal.SIGTERM, before)  # the interrupted clean-up left the shell's handler
    assert code == 130 and err.strip().splitlines()[-1] == "gearkit gear: interrupted"


def test_ctrl_c_while_the_command_loads_exits_130(capsys, monkeypatch):
    """An interrupt before the command runs (its modules still importing) is no traceback either."""
    import gearkit.cli.lean

    def interrupted(name):
        raise KeyboardInterrupt

    monkeypatch.setattr(gearkit.cli.lean.importlib, "import_module", interrupted)
    code, _, err = run(capsys, "gear", "-z", "20", "-m", "2")
    assert code == 130 and one_error_line(err) == "gearkit: interrupted"


def test_internal_error_is_one_line_with_a_debug_hint(capsys, monkeypatch):
    import gearkit.cli.gear

    def bug(args):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(gearkit.cli.gear, "build", bug)
    code, _, err = run(capsys, "gear", "-z", "20", "-m", "2")
    line = one_error_line(err)
    assert code == 70 and "internal error: ZeroDivisionError" in line and "--debug" in line
    with pytest.raises(ZeroDivisionError):
        main(["gear", "-z", "20", "-m", "2", "--debug"])


@pytest.mark.parametrize("argv, field", [
    (["gear", "-z", "20", "-m", "2", "--tol", "1e-12", "-o", "{t}/g.svg"], "tol"),
    (["gear", "-z", "20", "-m", "2", "--tol", "1e-11", "-o", "{t}/g.svg"], "tol"),
    (["gear", "-z", "20", "-m", "2", "--helix-angle-deg", "20", "--width", "20", "--tol", "1e-6", "-o", "{t}/h.stl"],
     "--tol"),
    (["rack", "-m", "2", "-n", "10000", "-o", "{t}/r.stl"], "--bar-teeth"),
    (["rack", "-m", "2", "-n", "100001"], "--bar-teeth"),
    (["rack", "-m", "2", "-n", "0"], "--bar-teeth"),
    (["pair", "--z1", "20", "--z2", "40", "-m", "2", "--width", "10", "--sweep", "100000"], "--sweep"),
    (["contact", "--z1", "20", "--z2", "40", "-m", "2", "--steps", "1000000"], "--steps"),
])
def test_work_that_would_hang_or_fill_a_disk_is_refused(capsys, tmp_path, argv, field):
    code, _, err = run(capsys, *[a.replace("{t}", str(tmp_path)) for a in argv])
    line = one_error_line(err)
    assert code == 2 and f"{field}:" in line
    if "about" in line:  # a size refusal says its estimate and the override
        assert "--max-points" in line
    assert list(tmp_path.iterdir()) == []


def test_max_points_lets_a_refused_output_through(capsys, tmp_path):
    argv = ["rack", "-m", "2", "-n", "50", "-o", str(tmp_path / "r.svg")]
    assert main(["--max-points", "10", *argv]) == 2
    assert "--max-points" in capsys.readouterr().err
    assert main(["--max-points", "1000000", *argv]) == 0
    assert (tmp_path / "r.svg").is_file()


def test_written_files_are_0644(capsys, tmp_path):
    old = os.umask(0o022)
    try:
        assert main(["blocking", "--z1", "13", "--z2", "16", "-o", str(tmp_path / "c.json")]) in (0, 1)
        assert main(["gear", "-z", "20", "-m", "2", "-o", str(tmp_path / "g.svg")]) == 0
    finally:
        os.umask(old)
    for f in tmp_path.iterdir():
        assert f.stat().st_mode & 0o777 == 0o644, f


def test_version_and_python_dash_m(capsys):
    with pytest.raises(SystemExit) as exc:
        build_parser().parse_args(["--version"])
    assert exc.value.code == 0 and capsys.readouterr().out.startswith("gearkit ")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    res = subprocess.run([sys.executable, "-m", "gearkit", "--version"], capture_output=True, text=True, env=env)
    assert res.returncode == 0 and res.stdout.startswith("gearkit ")


@pytest.mark.parametrize("argv, field", [
    (["gear", "-z", "20", "-m", "2", "--cutter-teeth", "0"], "--cutter-teeth"),
    (["rack", "-m", "2", "--cutter-teeth", "0"], "--cutter-teeth"),
    (["gear", "-z", "20", "-m", "2", "--herringbone", "--width", "20", "-o", "{t}/h.stl"], "herringbone"),
    (["pair", "--z1", "20", "--z2", "40", "-m", "2", "--width", "10", "--herringbone"], "herringbone"),
])
def test_nonsense_is_refused_not_ignored(capsys, tmp_path, argv, field):
    code, _, err = run(capsys, *[a.replace("{t}", str(tmp_path)) for a in argv])
    assert code == 2 and f"{field}:" in one_error_line(err)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("argv", [
    ["gear", "-z", "20", "-m", "2", "-o", "{t}/g.svg"],
    ["gear", "-z", "20", "-m", "2", "--json", "-o", "{t}/g.dxf"],
    ["rack", "-m", "2", "-n", "3", "--json", "-o", "{t}/r.csv"],
    ["pair", "--z1", "20", "--z2", "40", "-m", "2", "--width", "5", "-o", "{t}/p.stl"],
])
def test_every_write_says_wrote_file(capsys, tmp_path, argv):
    argv = [a.replace("{t}", str(tmp_path)) for a in argv]
    code, out, err = run(capsys, *argv)
    assert code in (0, 1)
    assert f"wrote {argv[-1]}" in out + err
    if "--json" in argv:
        json.loads(out)  # the line goes to stderr, stdout stays one JSON object

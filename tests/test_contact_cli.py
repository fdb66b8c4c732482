"""``gearkit contact`` and the simulation's findings in the design check; plots.

Oracles: the pair geometry's formula values (contact ratio, backlash), the formula findings the
simulated ones are compared with, and the PNG/SVG file signatures.
"""
import json

import pytest

from gearkit.checks import CheckLimits, check_pair
from gearkit.checks.report import Finding
from gearkit.checks.simulated import simulated_findings
from gearkit.cli import contact as contact_cli
from gearkit.cli.parser import ArgumentParser
from gearkit.contact import analyse_pair, plot_path_of_contact, plot_transmission_error
from gearkit.contact.analysis import Interference
from gearkit.pair import PairSpec, pair_geometry

EPS_TOL = 1e-3


def _run(argv, capsys):
    parser = ArgumentParser(prog="gearkit")  # the command line's parser: it knows the renamed flags' action
    sub = parser.add_subparsers(dest="command")
    contact_cli.register(sub)
    args = parser.parse_args(["contact", *argv])
    code = args.run(args)
    return code, capsys.readouterr().out


def test_json_has_the_issue_keys(capsys):
    code, out = _run(["--z1", "18", "--z2", "41", "-m", "2", "--x1", "0.3", "--x2", "-0.1", "--steps", "32",
                      "--json"], capsys)
    data = json.loads(out)
    assert code == 0
    for key in ("contact_ratio_simulated", "transmission_error_max", "backlash"):
        assert isinstance(data[key], float)
    assert set(data["interference"]) >= {"found", "max_depth", "where"}
    g = pair_geometry(PairSpec(18, 41, 2.0, 0.3, -0.1))
    assert data["contact_ratio_simulated"] == pytest.approx(g.contact_ratio, abs=EPS_TOL)
    assert data["contact_ratio_formula"] == pytest.approx(g.contact_ratio, abs=1e-12)
    assert data["interference"] == {**data["interference"], "found": False, "max_depth": 0.0, "where": []}
    assert [f["id"] for f in data["findings"]] == ["contact_ratio.simulated", "interference.simulated",
                                                   "backlash.simulated", "transmission_error.simulated"]


def test_jamming_pair_fails_with_depth(capsys):
    """Both shifts and a centre distance below the tight mesh: the teeth jam (exit status 1)."""
    code, out = _run(["--z1", "20", "--z2", "40", "-m", "1", "--x1", "0", "--x2", "0", "--center-distance",
                      "29.95", "--steps", "16", "--json"], capsys)
    data = json.loads(out)
    assert code == 1
    assert data["interference"]["found"] and "jamming" in data["interference"]["where"]
    assert data["backlash"] == pytest.approx(pair_geometry(PairSpec(20, 40, 1.0, center_distance=29.95)).backlash,
                                             abs=1e-9)


def test_text_summary_and_plots(tmp_path, capsys):
    te, path = tmp_path / "te.png", tmp_path / "path.svg"
    code, out = _run(["--z1", "12", "--z2", "24", "-m", "1", "--steps", "32", "-o", str(te), "-o", str(path)],
                     capsys)
    assert code == 0
    assert "contact ratio   simulated 1.274" in out
    assert "interference.simulated" in out and "clear each other" in out
    assert te.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert b"<svg" in path.read_bytes()[:1000]
    assert not list(tmp_path.glob(".gearkit-*"))  # atomic writes leave no temporary files


def test_registered_in_the_gearkit_command(capsys):
    from gearkit.cli import main

    assert main(["contact", "--z1", "20", "--z2", "40", "-m", "1", "--steps", "8"]) == 0
    assert "backlash  0.00000 mm circular" in capsys.readouterr().out
    assert main(["contact", "--z1", "20", "-m", "1"]) == 2  # bad input: no z2


def test_bad_plot_suffix_is_a_spec_error(tmp_path):
    from gearkit.errors import SpecError

    res = analyse_pair(PairSpec(20, 40, 1.0), 16)
    with pytest.raises(SpecError, match="output"):
        plot_transmission_error(res, tmp_path / "te.pdf")
    assert plot_path_of_contact(res, tmp_path / "p.png").endswith("p.png")


def test_check_pair_simulate_option_reports_beside_the_formulas():
    """The 12/24 pair: the formula flags interference.1, the generated teeth clear each other: the
    simulated finding warns about the disagreement; its contact ratio sits beside the formula's."""
    fast = check_pair(PairSpec(12, 24, 1.0))
    assert "contact_ratio.simulated" not in fast.report  # the default check stays formula-only
    rep = check_pair(PairSpec(12, 24, 1.0), simulate=True).report
    assert rep["interference.1"].status == "fail"
    sim = rep["interference.simulated"]
    assert sim.status == "warn" and "interference.1" in sim.message
    assert rep["contact_ratio.simulated"].value == pytest.approx(rep["contact_ratio"].value, abs=EPS_TOL)
    assert rep["backlash.simulated"].status == "ok"


def test_simulated_interference_is_flagged_even_when_the_formulas_pass():
    """The finding logic on its own: an overlap the formula findings did not predict fails, and says so."""
    spec = PairSpec(20, 40, 1.0)
    g = pair_geometry(spec)
    clean = analyse_pair(spec, 16)
    event = {"kind": "tip-fillet", "depth": 0.01, "driver_angle": 0.1, "point": [0.0, 10.0],
             "driver_feature": "fillet", "mate_feature": "tip", "side": "working", "step": 3}
    found = Interference(True, 0.01, 0.001, ("tip-fillet",), 0.1, (0.0, 10.0), (event,))
    faked = type(clean)(**{**clean.__dict__, "interference": found})
    formula_ok = [Finding("interference.1", "ok", 1.0, 0.0, "fine", "min")]
    out = {f.id: f for f in simulated_findings(spec, g, formula_ok, CheckLimits(), faked)}
    assert out["interference.simulated"].status == "fail"
    assert "the formulas miss it" in out["interference.simulated"].message
    formula_bad = [Finding("interference.1", "fail", -1.0, 0.0, "digs in", "min")]
    out = {f.id: f for f in simulated_findings(spec, g, formula_bad, CheckLimits(), faked)}
    assert "agree" in out["interference.simulated"].message


def test_example_script_runs(tmp_path, capsys):
    import runpy
    import sys
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "examples" / "contact_analysis.py"
    argv = sys.argv
    sys.argv = [str(path), str(tmp_path)]
    try:
        runpy.run_path(str(path), run_name="__main__")
    finally:
        sys.argv = argv
    assert {p.name for p in tmp_path.iterdir()} == {"te_12_24.png", "path_12_24.svg", "te_internal.png",
                                                   "path_cycloid.png"}
    out = capsys.readouterr().out
    assert "the teeth jam below a = 30.0000000000 mm (formula 30.0000000000)" in out

"""``gearkit check``, in process: exit status 0/1/2, the JSON keys, design files, the table."""
import json
import math
from pathlib import Path

import pytest

import gearkit.cli as cli
from gearkit.checks import check_pair, load_design
from gearkit.pair import PairSpec, pair_geometry

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "design.toml"
TOP_KEYS = {"ok", "center_distance", "reference_center_distance", "working_pressure_angle_deg",
            "center_distance_modification_coeff", "tip_shortening_coeff", "sum_shift_coeff", "contact_ratio",
            "gears", "findings"}
GEAR_KEYS = {"teeth", "shift_coeff", "reference_diameter", "base_diameter", "tip_diameter", "root_diameter",
             "form_diameter", "tip_thickness", "undercut"}
FINDING_KEYS = {"id", "status", "value", "limit", "message"}


@pytest.fixture(autouse=True)
def only_check(monkeypatch):
    """Register just this command, so the tests do not depend on the other commands' modules."""
    monkeypatch.setattr(cli, "COMMANDS", ("check",))


def run(argv, capsys):
    code = cli.main(["check", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_json_keys_and_values(capsys):
    code, out, err = run(["--z1", "18", "--z2", "41", "-m", "2", "--x1", "0.3", "--x2", "-0.1", "--json"], capsys)
    assert code == 0 and err == ""
    data = json.loads(out)
    assert TOP_KEYS <= set(data)
    assert set(data["contact_ratio"]) >= {"transverse", "overlap", "total"}
    assert all(GEAR_KEYS <= set(g) for g in data["gears"]) and len(data["gears"]) == 2
    assert all(FINDING_KEYS <= set(f) for f in data["findings"])
    assert data["ok"] is True
    g = pair_geometry(PairSpec(18, 41, 2.0, 0.3, -0.1))
    assert data["center_distance"] == pytest.approx(g.center_distance, rel=1e-15)
    assert data["working_pressure_angle_deg"] == pytest.approx(math.degrees(g.working_pressure_angle), rel=1e-15)
    assert data["sum_shift_coeff"] == pytest.approx(0.2, abs=1e-15)
    assert data["reference_center_distance"] == pytest.approx(59.0, rel=1e-15)
    assert data["gears"][0]["reference_diameter"] == pytest.approx(36.0, rel=1e-15)


def test_exit_status_one_when_a_finding_fails(capsys):
    code, out, _ = run(["--z1", "12", "--z2", "24", "-m", "1", "--json"], capsys)
    data = json.loads(out)
    assert code == 1 and data["ok"] is False
    failing = [f["id"] for f in data["findings"] if f["status"] == "fail"]
    assert failing == ["interference.1"]
    assert data["gears"][0]["undercut"] is True
    assert data["contact_ratio"]["transverse"] < data["contact_ratio"]["transverse_nominal"]


@pytest.mark.parametrize("argv,needle", [
    (["--z1", "12", "--z2", "24", "-m", "-1"], "module"),
    (["--z1", "12", "-m", "1"], "--z2"),
    (["--z1", "12", "--z2", "40", "-m", "1", "--internal"], "--cutter-teeth"),
    (["--z1", "12", "--z2", "24", "-m", "1", "--split", "equal"], "split"),
    (["--z1", "12", "--z2", "24", "-m", "1", "--center-distance", "19", "--x2", "0.1"], "x2"),
    (["--z1", "12", "--z2", "24", "-m", "1", "--rack", "iso53a", "--pressure-angle-deg", "25"], "--pressure-angle-deg"),
    (["--z1", "twelve", "--z2", "24", "-m", "1"], "invalid int"),
    (["missing.toml"], "cannot read"),
])
def test_bad_input_exits_two_with_one_line(argv, needle, capsys):
    code, out, err = run(argv, capsys)
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert needle in err and "Traceback" not in err
    assert len(lines) == 1  # argparse errors too (gearkit.cli.ArgumentParser.error)


def test_design_file_equals_flags(capsys):
    code, out, _ = run([str(EXAMPLE), "--json"], capsys)
    assert code == 0
    from_file = json.loads(out)
    code, out, _ = run(["--z1", "18", "--z2", "41", "-m", "2", "--helix-angle-deg", "15", "--width", "20",
                        "--center-distance", "62", "--rack", "iso53a", "--thinning2", "0.04", "--json"], capsys)
    from_flags = json.loads(out)
    assert code == 0 and from_file == from_flags
    assert from_file["center_distance"] == 62.0
    assert from_file["backlash"]["transverse"] > 0


def test_flags_override_the_design_file(capsys):
    code, out, _ = run([str(EXAMPLE), "--z1", "20", "--json"], capsys)
    assert code in (0, 1) and json.loads(out)["gears"][0]["teeth"] == 20


@pytest.mark.parametrize("text,needle", [
    ("module = 2\n[gear1]\nteeth = 18\n[gear2]\nteeth = 41\ncolour = 'red'\n", "gear2.colour"),
    ("module = 2\n[gear1]\nteeth = 18\n", "gear2"),
    ("module = 2\n[gear1]\nteeth = 18\ntool = 'iso53z'\n[gear2]\nteeth = 41\n", "gear1.tool"),
    ("module = 2\n[gear1]\nteeth = 18\n[gear2]\nteeth = 41\n[limits]\nmin_contact_ratio = 0.5\n", "min_contact_ratio"),
    ("module = 2\n[gear1\nteeth = 18\n", "not valid TOML"),
])
def test_bad_design_files(tmp_path, capsys, text, needle):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    code, out, err = run([str(path)], capsys)
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1


def test_internal_design_file(tmp_path, capsys):
    """The textbook's internal example as a design file reproduces its numbers (digest 3.2)."""
    path = tmp_path / "internal.toml"
    path.write_text('kind = "internal"\nmodule = 8.0\nring_shift = "cutter"\n'
                    '[gear1]\nteeth = 46\nshift = 0.0\ntool = { type = "shaper", teeth = 20, addendum = 1.3 }\n'
                    '[gear2]\nteeth = 49\nshift = 0.52\ntool = { type = "shaper", teeth = 20, addendum = 1.3 }\n')
    spec, _ = load_design(path)
    assert spec.kind == "internal" and spec.tools[1].teeth == 20
    code, out, _ = run([str(path), "--json"], capsys)
    data = json.loads(out)
    assert code == 0
    assert data["center_distance"] == pytest.approx(14.9869, abs=5e-5)
    assert data["contact_ratio"]["transverse_nominal"] == pytest.approx(1.92561, abs=5e-6)
    assert [g["tip_diameter"] / 2 for g in data["gears"]] == pytest.approx([193.173, 190.987], abs=5e-4)
    assert {f["id"] for f in data["findings"]} >= {"exit_jamming", "tip_interference", "trimming.plunge",
                                                    "trimming.nu", "min_teeth.difference"}


def test_center_distance_rules(capsys):
    def shifts(argv):
        code, out, _ = run(["--z1", "18", "--z2", "41", "-m", "2", *argv, "--json"], capsys)
        data = json.loads(out)
        return code, [g["shift_coeff"] for g in data["gears"]], data

    _, (x1, x2), data = shifts(["--center-distance", "60", "--split", "equal"])
    assert x1 == pytest.approx(x2, abs=1e-12) and data["center_distance"] == 60.0
    _, (x1, x2), _ = shifts(["--center-distance", "60", "--x1", "0.5"])
    assert x1 == 0.5 and x1 + x2 == pytest.approx(0.530249, abs=5e-7)
    code, _, data = shifts(["--center-distance", "59.9", "--x1", "0.3", "--x2", "0.2"])  # below tight: jammed
    assert code == 1 and next(f for f in data["findings"] if f["id"] == "backlash")["status"] == "fail"


def test_human_table_marks_failures(capsys):
    code, out, _ = run(["--z1", "12", "--z2", "24", "-m", "1"], capsys)
    assert code == 1
    fail_lines = [line for line in out.splitlines() if "!! FAIL" in line]
    assert len(fail_lines) == 1 and "interference.1" in fail_lines[0]
    assert out.strip().splitlines()[-1] == "result: FAIL (1 failing, 2 warnings)"
    assert sum(" ! warn" in line for line in out.splitlines()) == 2


def test_rack_pair_and_internal_flags(capsys):
    code, out, _ = run(["--z1", "14", "--rack-pair", "-m", "2", "--x1", "0.2", "--json"], capsys)
    assert code == 0 and json.loads(out)["kind"] == "rack"
    code, out, _ = run(["--z1", "46", "--z2", "49", "-m", "8", "--x2", "0.52", "--internal", "--cutter-teeth", "20",
                        "--cutter-addendum", "1.3", "--pinion-cutter-teeth", "20", "--ring-shift", "cutter", "--json"], capsys)
    data = json.loads(out)
    assert code == 0 and data["status"] == "warn"
    assert data["center_distance"] == pytest.approx(14.9869, abs=5e-5)


def test_help_documents_the_ring_shift_sign(capsys):
    with pytest.raises(SystemExit):
        cli.build_parser().parse_args(["check", "--help"])
    out = capsys.readouterr().out
    assert "thinner" in out and "tip (inner) diameter larger" in out.replace("\n", " ").replace("  ", " ")


def test_limits_flags_change_the_verdict(capsys):
    argv = ["--z1", "13", "--z2", "60", "-m", "1", "--x1", "0.5", "--tip-rule", "standard", "--json"]
    _, out, _ = run(argv, capsys)
    base = {f["id"]: f for f in json.loads(out)["findings"]}
    _, out, _ = run(argv + ["--min-tip-thickness", "0.5"], capsys)
    strict = {f["id"]: f for f in json.loads(out)["findings"]}
    assert base["pointing.1"]["status"] == "ok" and strict["pointing.1"]["status"] == "warn"
    assert check_pair(PairSpec(13, 60, 1.0, 0.5, tip_rule="standard")).report["pointing.1"].value == \
        pytest.approx(base["pointing.1"]["value"], rel=1e-15)

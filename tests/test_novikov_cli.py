"""``gearkit novikov`` in-process: JSON keys and values, exit statuses, rack files, atomic 2D export."""
import json

import pytest

from gearkit.cli import main
from gearkit.families.novikov.presets import PRESETS_FILE

PAIR = ["novikov", "--z1", "20", "--z2", "60", "-m", "4", "--helix-angle-deg", "15"]


def _json(capsys, argv):
    code = main(argv + ["--json"])
    return code, json.loads(capsys.readouterr().out)


def test_json_of_the_worked_pair(capsys):
    code, out = _json(capsys, PAIR + ["--width", "60"])
    assert code == 0 and out["status"] == "warn"  # the preset racks are unverified
    assert out["center_distance"] == pytest.approx(165.6442, abs=0.6e-4)
    assert out["overlap_ratio"] == pytest.approx(1.23577, abs=0.6e-5)
    assert out["contact_angle_transverse_deg"] == pytest.approx(24.7466, abs=0.6e-4)
    assert out["contact_radii"][0] == pytest.approx([43.8472, 122.1445], abs=0.6e-4)
    ids = {f["id"]: f for f in out["findings"]}
    assert ids["transverse_contact_ratio"]["status"] == "ok"
    assert ids["mesh.interference"]["status"] == "ok" and ids["mesh.contact.1"]["status"] == "ok"
    assert len(out["gears"]) == 2 and len(out["simulated_contacts"]) == 2


def test_exit_status_follows_the_findings(capsys):
    code, out = _json(capsys, PAIR + ["--width", "40", "--no-mesh"])
    assert code == 1 and out["status"] == "fail"
    f = next(f for f in out["findings"] if f["id"] == "overlap_ratio")
    assert f["status"] == "fail" and "increase the helix angle beta or the face width b" in f["message"]
    assert main(PAIR + ["--width", "60", "--rack", "single-arc", "--no-mesh"]) == 0
    text = capsys.readouterr().out
    assert "single-arc pair" in text and "UNVERIFIED" in text and "result: WARN" in text


def test_bad_input_exits_2_with_a_reason(capsys):
    assert main(PAIR + ["--width", "60", "--rack", "gost"]) == 2
    assert "unknown rack 'gost'" in capsys.readouterr().err
    assert main(["novikov", "--z1", "20", "--z2", "60", "-m", "4", "--width", "60"]) == 2
    assert "--helix-angle-deg: is required" in capsys.readouterr().err
    assert main(PAIR + ["--width", "60", "--center-distance", "170"]) == 2
    assert "center_distance" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["pair.stl", "pair.svg"])
def test_a_pair_that_does_not_mesh_is_not_written_and_fails(tmp_path, capsys, name):
    """Placing the gears in mesh needs their contact: where it does not exist (a_w beyond the working
    arcs' reach) the report fails and no file is written (exit 1, a failing design, not bad input)."""
    path = tmp_path / name
    argv = ["novikov", "--z1", "20", "--z2", "60", "-m", "1", "--helix-angle-deg", "15", "--width", "20",
            "--center-distance", "41.7", "-o", str(path)]
    assert main(argv) == 1
    cap = capsys.readouterr()
    assert "mesh.contact.0" in cap.out and "not written: the gears cannot be placed in mesh" in cap.err
    assert not path.exists() and list(tmp_path.iterdir()) == []
    assert main(argv + ["--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert out["output"]["written"] is False and out["status"] == "fail"


def test_rack_file(tmp_path, capsys):
    text = PRESETS_FILE.read_text()
    body = text[text.index("[dca24.rack]"):text.index("[single-arc]")].replace("[dca24.rack]", "[rack]")
    f = tmp_path / "mine.toml"
    f.write_text('title = "mine"\n' + body)
    code, out = _json(capsys, PAIR + ["--width", "60", "--rack", str(f), "--no-mesh"])
    assert code == 0 and out["racks"] == "mine"
    assert out["center_distance_window"] == pytest.approx([-0.0328 * 4, 0.0286 * 4], abs=0.6e-4 * 4)
    f.write_text(body.replace("1.42", "1.25"))
    assert main(PAIR + ["--width", "60", "--rack", str(f)]) == 2
    assert "must exceed" in capsys.readouterr().err


def test_profile_export_is_written_atomically(tmp_path, capsys):
    out = tmp_path / "pair.svg"
    assert main(PAIR + ["--width", "60", "--no-mesh", "-o", str(out)]) == 0
    text = out.read_text()
    assert text.startswith("<svg") and text.count("<path") == 2  # both gears, placed in mesh
    assert not [p for p in tmp_path.iterdir() if p.name != "pair.svg"]  # no temporary file left behind
    assert main(PAIR + ["--width", "60", "--no-mesh", "-o", str(tmp_path / "nowhere" / "p.svg")]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_helical_solids_through_the_solids_interface(tmp_path, capsys):
    """The pair placed in mesh as helical solids of opposite hands: their only overlap is faceting near the
    travelling contact points, so it vanishes faster than the mesh tolerance."""
    pytest.importorskip("gearkit.solids")
    volumes = []
    for tol in (0.02, 0.005):
        code, out = _json(capsys, PAIR + ["--width", "60", "--no-mesh", "--tol", str(tol), "-o",
                                          str(tmp_path / "pair.obj")])
        assert code == 0 and out["output"]["parts"] == ["gear1", "gear2"] and out["output"]["achieved"] <= tol
        volumes.append(out["output"]["interference_volume"])
    assert volumes[1] < volumes[0] / 4 ** 1.5
    text = (tmp_path / "pair.obj").read_text()
    assert "gear1" in text and "gear2" in text
    code, out = _json(capsys, PAIR + ["--width", "60", "--no-mesh", "-o", str(tmp_path / "gear.stl")])
    assert code == 0 and out["output"]["parts"] == ["gear1"] and (tmp_path / "gear.stl").stat().st_size > 1000
    code, out = _json(capsys, PAIR + ["--width", "60", "--no-mesh", "--gear", "2", "-o", str(tmp_path / "w.stl")])
    assert out["output"]["parts"] == ["gear2"]


def test_example_script_runs(tmp_path, capsys):
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "examples" / "novikov_pair.py"
    spec = importlib.util.spec_from_file_location("novikov_pair_example", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.main(tmp_path)
    out = capsys.readouterr().out
    assert "result: WARN" in out and "b = 40 mm: fail" in out
    assert (tmp_path / "novikov_pair.svg").read_text().startswith("<svg")

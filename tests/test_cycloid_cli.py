"""`gearkit cycloidal-drive` and `gearkit cycloid` in-process: JSON keys and values, exit codes, exports.

Numbers are the reference digest's (cycloid §4 items 7, 8, 11, 13; "other gears" §1.5) and the
issue's (clock factors 0.95 A and 1.40 A, with A from a rolled circle).
"""
import json
import math

import pytest

from gearkit.cli import main
from gearkit.oracles.cycloid import clock_addendum_by_rolling

DRIVE = ["cycloidal-drive", "--pins", "12", "--lobes", "11", "--pin-circle-radius", "90", "--pin-radius", "7",
         "--eccentricity", "4", "--samples", "400"]


def _run(capsys, argv, code=0):
    assert main(argv) == code
    return capsys.readouterr()


def test_drive_json_has_the_issue_keys_and_the_digest_values(capsys):
    info = json.loads(_run(capsys, DRIVE + ["--json"]).out)
    for key in ("contact_ratio", "pins_in_contact", "load_carrying_pins", "min_curvature_radius",
                "active_pin_arc_deg", "backlash_rad", "findings"):
        assert key in info
    assert info["contact_ratio"] == pytest.approx(6.0, abs=1e-9)
    assert info["pins_in_contact"] == 12 and info["load_carrying_pins"] == 6
    assert info["min_curvature_radius"] == pytest.approx(27.9916, abs=1e-4)
    assert info["active_pin_arc_deg"] == pytest.approx(32.231, abs=1e-3)
    assert info["backlash_rad"] == 0.0 and info["status"] == "ok"
    assert {f["id"] for f in info["findings"]} >= {"meshing.condition", "curtate", "profile.closed", "pins.overlap",
                                                   "looping", "contact_ratio", "backlash"}


def test_drive_text_names_pins_in_contact(capsys):
    out = _run(capsys, DRIVE).out
    assert "pins in contact: 12 (6 load-carrying per direction)" in out
    assert "result: OK" in out


def test_drive_with_equidistant_modification(capsys):
    info = json.loads(_run(capsys, DRIVE + ["--equidistant-mod", "0.02", "--json"]).out)
    assert info["backlash_rad"] == pytest.approx(0.45455e-3, rel=0.01)
    assert info["pins_in_contact"] == 1 and info["load_carrying_pins"] == 1


def test_failing_design_exits_1_and_bad_input_exits_2(capsys):
    looping = ["cycloidal-drive", "--pins", "40", "--lobes", "39", "--pin-circle-radius", "100", "--pin-radius", "5.5",
               "--eccentricity", "2.25", "--samples", "50", "--json"]
    info = json.loads(_run(capsys, looping, 1).out)
    assert {f["id"]: f["status"] for f in info["findings"]}["looping"] == "fail"
    err = _run(capsys, DRIVE[:4] + ["12"] + DRIVE[5:], 2).err  # lobes = pins
    assert "lobes" in err and "error" in err
    _run(capsys, DRIVE + ["-o", "disc.xyz"], 2)


@pytest.mark.parametrize("name", ["disc.svg", "disc.dxf", "disc.csv", "disc.stl", "drive.obj"])
def test_drive_exports(tmp_path, capsys, name):
    out = tmp_path / name
    info = json.loads(_run(capsys, DRIVE + ["--samples", "20", "-o", str(out), "--json"]).out)
    assert out.stat().st_size > 1000 and not list(tmp_path.glob("*.part"))
    if name.endswith(".dxf"):
        ezdxf = pytest.importorskip("ezdxf")
        loops = list(ezdxf.readfile(str(out)).modelspace())
        assert len(loops) == 1 + 1 + 6 and all(p.closed for p in loops)  # outline, bore, output holes
    if name == "disc.stl":
        import trimesh

        mesh = trimesh.load(str(out))
        assert mesh.is_watertight and mesh.volume > 0
        assert info["output"]["parts"] == ["disc"]
    if name == "drive.obj":
        assert info["output"]["parts"] == ["disc", "pins", "housing", "output_pins"]
        assert all(v > 0 for v in info["output"]["volumes"].values())


def test_clock_gearing_json(capsys):
    info = json.loads(_run(capsys, ["cycloid", "-m", "1", "--pinion-teeth", "8", "--wheel-teeth", "64", "--clock",
                                    "--json"]).out)
    big_a = clock_addendum_by_rolling(8, 64)
    assert info["wheel_addendum_factor"] == pytest.approx(0.95 * big_a, abs=1e-9)
    assert info["wheel_addendum_radius_factor"] == pytest.approx(1.40 * big_a, abs=1e-9)
    assert info["rolling_radius1"] == pytest.approx(2.0)  # r1/2: radial pinion flanks
    assert info["contact_ratio"] == pytest.approx(info["contact_ratio_generated"], rel=1e-6)


def test_cycloid_pair_and_pin_gearing(tmp_path, capsys):
    info = json.loads(_run(capsys, ["cycloid", "-m", "1", "--pinion-teeth", "30", "--wheel-teeth", "30",
                                    "--rolling-radius", "5.625", "--json"]).out)
    assert info["contact_ratio"] == pytest.approx(1.8723, abs=1e-4)  # digest "other gears" §1.5
    out = tmp_path / "pair.obj"
    pins = _run(capsys, ["cycloid", "-m", "1", "--pinion-teeth", "8", "--wheel-teeth", "40", "--pin-radius", "0.8",
                         "--addendum", "2.0", "--json", "-o", str(out)]).out
    info = json.loads(pins)
    assert info["output"]["parts"] == ["wheel", "pins"] and out.stat().st_size > 1000
    assert {f["id"] for f in info["findings"]} == {"flank.loop", "pointed", "contact_ratio"}
    svg = tmp_path / "pair.svg"
    _run(capsys, ["cycloid", "-m", "1", "--pinion-teeth", "12", "--wheel-teeth", "30", "-o", str(svg)])
    assert svg.read_text().count("<path") == 2
    assert math.isfinite(json.loads(_run(capsys, ["cycloid", "-m", "1", "--pinion-teeth", "12", "--wheel-teeth",
                                                  "30", "--json"]).out)["contact_ratio"])
    _run(capsys, ["cycloid", "-m", "1", "--pinion-teeth", "12", "--wheel-teeth", "30", "--rolling-radius", "1",
                  "2", "3"], 2)


def test_example_script_runs(tmp_path):
    import runpy
    import sys

    path = __import__("pathlib").Path(__file__).resolve().parents[1] / "examples" / "cycloidal_drive.py"
    argv = sys.argv
    sys.argv = [str(path), str(tmp_path)]
    try:
        runpy.run_path(str(path), run_name="__main__")
    finally:
        sys.argv = argv
    assert {p.name for p in tmp_path.iterdir()} >= {"disc.dxf", "disc.stl", "drive.obj"}

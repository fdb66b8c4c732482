"""`gearkit gear` (2D) and `gearkit rack` in-process: JSON keys, values, atomic exports, bad input."""
import json
import math

import pytest

from gearkit.cli import main


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_gear_json_has_the_documented_keys_and_textbook_values(capsys):
    info = _json(capsys, ["gear", "-z", "13", "-m", "1", "-x", "0", "--json"])
    for key in ("family", "teeth", "module", "shift_coeff", "reference_diameter", "base_diameter", "tip_diameter",
                "root_diameter", "form_diameter", "tooth_thickness", "tip_thickness", "undercut", "pointed"):
        assert key in info
    assert info["undercut"] is True and info["pointed"] is False  # z = 13 < 17 with x = 0
    assert info["tip_thickness"] == pytest.approx(0.634245, abs=5e-7)  # digest §1.7
    assert info["tolerance"]["achieved"] <= info["tolerance"]["requested"]


def test_internal_gear_from_the_cli_matches_the_textbook(capsys):
    info = _json(capsys, ["gear", "-z", "49", "-m", "8", "-x", "0.52", "--internal", "--cutter-teeth", "20",
                          "--cutter-addendum", "1.3", "--ring-shift", "cutter", "--json"])
    assert info["tooth_thickness"] == pytest.approx(9.17132, abs=5e-6)


@pytest.mark.parametrize("ext", ["svg", "dxf", "csv", "json"])
def test_profile_exports_are_written_whole(tmp_path, capsys, ext):
    out = tmp_path / f"g.{ext}"
    assert main(["gear", "-z", "20", "-m", "2", "-o", str(out)]) == 0
    assert out.stat().st_size > 1000
    assert not list(tmp_path.glob("*.part"))
    if ext == "dxf":
        import ezdxf
        poly = list(ezdxf.readfile(str(out)).modelspace())[0]
        assert poly.closed and len(poly) > 20 * 10


def test_bad_input_exits_2_with_a_one_line_message(tmp_path, capsys):
    assert main(["gear", "-z", "2", "-m", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "teeth" in err[0]
    assert main(["gear", "-z", "20", "-m", "1", "-o", str(tmp_path / "x.png")]) == 2
    assert "allowed" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())
    assert main(["gear", "-z", "20", "-m", "1", "-o", str(tmp_path / "missing" / "x.svg")]) == 2


def test_rack_command_reports_the_basic_rack(capsys):
    info = _json(capsys, ["rack", "-m", "2", "--json"])
    assert info["pitch"] == pytest.approx(2 * math.pi)
    assert info["tooth_thickness"] == pytest.approx(math.pi, abs=1e-12)
    assert (info["tip_height"], info["root_height"]) == pytest.approx((2.0, -2.5))


def test_rack_bar_solid_volume_is_profile_area_times_width(tmp_path, capsys):
    import numpy as np
    import trimesh

    from gearkit.families.involute.rack import RackSpec, rack_profile

    out = tmp_path / "rack.stl"
    info = _json(capsys, ["rack", "-m", "2", "-n", "5", "--width", "12", "--height", "9", "--tol", "0.002",
                          "-o", str(out), "--json"])
    mesh = trimesh.load(str(out))
    assert mesh.is_watertight
    prof = rack_profile(RackSpec(2.0))
    line = prof.outline(1e-6, teeth=5)
    base = prof.tip_height - 9.0
    poly = np.concatenate([line, [[line[-1, 0], base], [line[0, 0], base]]])
    area = 0.5 * abs(np.sum(poly[:, 0] * np.roll(poly[:, 1], -1) - np.roll(poly[:, 0], -1) * poly[:, 1]))
    perimeter = np.sum(np.linalg.norm(np.diff(np.vstack([poly, poly[:1]]), axis=0), axis=1))
    bound = 0.002 * perimeter * 12  # every facet within tol of the exact surface
    assert abs(mesh.volume - area * 12) <= bound
    assert abs(info["volume"] - mesh.volume) < 1e-6 * mesh.volume

"""``gearkit cam``: JSON keys, exit codes, bad input naming the flag, exports, design files, solids, plots."""
import json
import math

import numpy as np
import pytest

from gearkit.cli import main

BASE = ["cam", "--prime-radius", "56.7702", "--roller-radius", "10", "--law", "cycloidal", "--rise", "20",
        "--rise-deg", "60", "--dwell-deg", "60", "--return-deg", "60"]


def run_json(capsys, args):
    code = main(args + ["--json"])
    return code, json.loads(capsys.readouterr().out)


def test_json_keys_and_values(capsys):
    code, out = run_json(capsys, BASE + ["--tol", "0.001"])
    assert code == 0
    assert set(out["pressure_angle_max_deg"]) == {"rise", "return"}
    assert abs(out["pressure_angle_max_deg"]["rise"] - 30.0) < 1e-3  # the digest's r0,min for 30 degrees
    assert out["undercut"] is False
    assert out["tolerance"]["requested"] == 0.001 and 0 < out["tolerance"]["achieved"] <= 0.001
    assert abs(out["min_curvature_radius"] - (30.9691 - 10.0)) < 1e-4  # digest rho_min - R_p
    assert "pressure_angle_friction_max_deg" not in out


@pytest.mark.parametrize("flag", [["--friction", "0.1"], ["--efficiency", "0.9"]])
def test_friction_adds_its_keys_and_raises_the_angles(capsys, flag):
    code, out = run_json(capsys, BASE + flag)
    assert code == 1  # r0 = 56.7702 keeps 30 degrees only without friction
    for kind in ("rise", "return"):
        assert out["pressure_angle_friction_max_deg"][kind] > out["pressure_angle_max_deg"][kind] + 2.0
    assert out["prime_radius_min_friction"] > out["prime_radius_min"] + 5.0
    if flag[0] == "--efficiency":
        assert abs(out["prime_radius_min_friction"] - 64.0605) < 1e-4  # digest table, eta = 0.9


@pytest.mark.parametrize("args, flag", [
    (["--prime-radius", "-5"], "--prime-radius"), (["--roller-radius", "-2"], "--roller-radius"),
    (["--rise-deg", "200", "--dwell-deg", "100", "--return-deg", "100"], "--rise-deg"),
    (["--offset", "70"], "--offset"), (["--rocker", "--pivot-distance", "200", "--arm-length", "50"], "--arm-length"),
    (["--rise", "-3"], "--rise"), (["--tol", "0"], "--tol"), (["-o", "cam.xyz"], "output")])
def test_bad_input_exits_2_naming_the_flag(capsys, tmp_path, args, flag):
    argv = list(BASE)
    for k in range(0, len(args)):
        if args[k] in argv and args[k].startswith("-") and k + 1 < len(args) and not args[k + 1].startswith("--"):
            i = argv.index(args[k])
            argv[i + 1] = args[k + 1]
    extra = [a for k, a in enumerate(args) if not (a in BASE or (k > 0 and args[k - 1] in BASE))]
    code = main(argv + extra)
    err = capsys.readouterr().err
    assert code == 2
    assert err.count("\n") == 1 and flag in err and "Traceback" not in err


@pytest.mark.parametrize("given, missing", [("--pivot-distance", "--arm-length"), ("--arm-length", "--pivot-distance")])
def test_a_rocker_without_its_other_length_names_it(capsys, given, missing):
    """A rocker needs both lengths: the one not typed is named as required (it read 'None must be a
    positive length')."""
    code = main(BASE + [given, "60"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and missing in err and "required" in err and "None" not in err


def test_csv_svg_dxf_exports_and_csv_header(tmp_path, capsys):
    for ext in ("csv", "svg", "dxf"):
        path = tmp_path / f"cam.{ext}"
        assert main(BASE + ["-o", str(path), "--tol", "0.001"]) == 0
        assert path.stat().st_size > 0
    lines = (tmp_path / "cam.csv").read_text().splitlines()
    assert lines[0].split(",")[1:] == ["x_mm", "y_mm"]
    pts = np.array([[float(v) for v in ln.split(",")[1:]] for ln in lines[1:]])
    r = np.hypot(pts[:, 0], pts[:, 1])
    assert abs(r.min() - 46.7702) < 1e-6 and abs(r.max() - 66.7702) < 1e-3  # r0 - R_p .. r0 + H - R_p


def test_mesh_output_with_a_bore_is_a_prism_of_the_outline(tmp_path, capsys):
    import trimesh

    path = tmp_path / "cam.stl"
    code = main(BASE + ["-o", str(path), "--width", "12", "--bore", "20", "--tol", "0.001", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    mesh = trimesh.load(path)
    assert mesh.is_watertight
    # volume = width x (cam area - bore area); the polygon areas are within tol x perimeter of the exact ones
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
    prof = cam_profile(CamSpec(56.7702, MotionProgram.rise_dwell_return(20.0, 60.0, 60.0, 60.0), roller_radius=10.0))
    outline = prof.outline(0.001)
    x, y = outline.T
    area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    expected = 12.0 * (area - math.pi * 10.0 ** 2)
    assert abs(mesh.volume - expected) <= 12.0 * 0.001 * 2 * math.pi * 10.0 + 1e-6 * expected
    assert abs(out["output"]["volume"] - mesh.volume) < 1e-3 * mesh.volume
    assert main(BASE + ["-o", str(tmp_path / "c.stl"), "--width", "5", "--bore", "95"]) == 2
    assert "--bore" in capsys.readouterr().err


def test_design_file_gives_the_same_cam_as_the_flags(tmp_path, capsys):
    design = tmp_path / "cam.toml"
    design.write_text('[cam]\nprime_radius = 56.7702\nroller_radius = 10.0\n\n'
                      '[[motion]]\nkind = "rise"\nspan_deg = 60\nlift = 20\nlaw = "cycloidal"\n\n'
                      '[[motion]]\nkind = "dwell"\nspan_deg = 60\n\n'
                      '[[motion]]\nkind = "return"\nspan_deg = 60\nlift = 20\n')
    _, by_flags = run_json(capsys, BASE)
    _, by_file = run_json(capsys, ["cam", str(design)])
    assert by_file["pressure_angle_max_deg"] == by_flags["pressure_angle_max_deg"]
    assert by_file["min_curvature_radius"] == by_flags["min_curvature_radius"]
    # the flags typed override the file, as in every command (a motion flag replaces the whole motion)
    _, smaller = run_json(capsys, ["cam", str(design), "--roller-radius", "6", "--offset", "5"])
    _, flags = run_json(capsys, BASE[:3] + ["--roller-radius", "6", "--offset", "5"] + BASE[5:])
    assert smaller == flags and smaller != by_file
    _, faster = run_json(capsys, ["cam", str(design), "--rise", "20", "--rise-deg", "45", "--return-deg", "60"])
    _, flags = run_json(capsys, BASE[:9] + ["--rise-deg", "45", "--return-deg", "60"])
    assert faster == flags
    assert main(["cam", str(design), "--rise-deg", "45"]) == 2  # a motion flag needs the whole motion
    assert "--rise:" in capsys.readouterr().err
    # the old spelling --design FILE reads it too, with one deprecation line
    code = main(["cam", "--design", str(design), "--json"])
    out, err = capsys.readouterr()
    assert code == 0 and json.loads(out) == by_file and err.count("is deprecated") == 1
    design.write_text('[cam]\nprime_radius = 50\nroler_radius = 5\n[[motion]]\nkind = "rise"\nspan_deg = 90\n')
    assert main(["cam", str(design)]) == 2
    assert "cam.roler_radius" in capsys.readouterr().err


def test_plot_is_written(tmp_path, capsys):
    path = tmp_path / "cam.png"
    assert main(BASE + ["--efficiency", "0.9", "--plot", str(path)]) == 1
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 20_000
    assert main(BASE + ["--plot", str(tmp_path / "cam.jpg")]) == 2



FLAT = [a for a in BASE if a not in ("--roller-radius", "10")] + ["--contact", "flat", "--prime-radius", "30"]


#: a flat rocker whose face swings several times as fast as the cam (tests/test_cam_flat.py STEEP): its
#: acceleration and jerk run to thousands, tick labels five and six characters wide
STEEP_FLAT_ROCKER = ["cam", "--contact", "flat", "--rocker", "--prime-radius", "20", "--pivot-distance", "24",
                     "--arm-length", "27.13", "--law", "polynomial_345", "--rise", "35", "--rise-deg", "20",
                     "--dwell-deg", "1.75", "--return-deg", "20"]


def _drawn(argv):
    """The cam picture of ``argv`` drawn on an Agg canvas: ``(figure, renderer)``."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from gearkit.cli import build_parser
    from gearkit.cli.cam import spec_from_args
    from gearkit.families.cam import cam_profile
    from gearkit.families.cam.plot import figure

    fig = figure(cam_profile(spec_from_args(build_parser("cam").parse_args(argv))))
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return fig, canvas.get_renderer()


@pytest.mark.parametrize("argv", [BASE, FLAT + ["--rocker", "--pivot-distance", "80", "--arm-length", "60"],
                                  STEEP_FLAT_ROCKER], ids=["roller", "flat-rocker", "steep-flat-rocker"])
def test_plot_every_label_and_tick_is_inside_the_picture(argv):
    """Everything drawn in each panel (its title, axis labels, the tick labels it draws, its legend) lies within
    the figure's frame: a wide tick label once pushed the acceleration's axis label past the left edge. No
    panel's labels run into a neighbour's."""
    fig, renderer = _drawn(argv)
    frame = fig.bbox
    boxes = [(ax, ax.get_tightbbox(renderer)) for ax in fig.axes]  # drawn ticks only, legends included
    assert [ax.get_ylabel().split("\n")[0] for ax in fig.axes[:4]] == ["s", "s'", "s''", "s'''"]
    for ax, box in boxes:
        assert frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1, \
            f"panel {ax.get_ylabel() or ax.get_title()!r} drawn at {box.extents}, outside {frame.extents}"
    for i, (a, box) in enumerate(boxes):
        for b, other in boxes[i + 1:]:
            inter = box.intersection(box, other)
            assert inter is None or inter.width * inter.height <= 0.0, \
                f"{a.get_ylabel()!r} and {b.get_ylabel()!r} overlap by {inter.width:.1f} x {inter.height:.1f} px"


@pytest.mark.parametrize("argv", [BASE, BASE + ["--rocker", "--pivot-distance", "90", "--arm-length", "70",
                                                "--friction", "0.2"], FLAT], ids=["roller", "rocker", "flat"])
def test_plot_legends_cover_no_line_and_no_other_panel(argv):
    """Every legend sits where no plotted point of its panel falls and overlaps no other panel; it stays inside
    the picture (a legend drawn over the cam once hid its pitch curve)."""
    fig, renderer = _drawn(argv)
    frame = fig.bbox
    legends = [(ax, ax.get_legend()) for ax in fig.axes if ax.get_legend() is not None]
    assert len(legends) == 2
    pts = np.vstack([a.transData.transform(line.get_xydata()) for a in fig.axes for line in a.get_lines()]
                    + [p.get_transform().transform(p.get_path().vertices) for a in fig.axes for p in a.patches])
    for ax, legend in legends:
        box = legend.get_window_extent(renderer)
        assert frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
        inside = (pts[:, 0] > box.x0) & (pts[:, 0] < box.x1) & (pts[:, 1] > box.y0) & (pts[:, 1] < box.y1)
        assert not inside.any(), f"{inside.sum()} plotted points under the legend"
        for other in fig.axes:
            if other is not ax:
                assert not box.overlaps(other.get_tightbbox(renderer)), "a legend over another panel"

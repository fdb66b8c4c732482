"""Issue 19: atlases at scale -- ``gearkit atlas`` writes a queryable dataset (a file per cell, an
index, a contact sheet), resumable and deterministic, on a local process pool and on a Dask cluster
started here (the same cell function)."""
import json

import pytest

from gearkit.checks import check_pair
from gearkit.cli import main
from gearkit.pair import PairSpec

ARGS = ["atlas", "--z1", "12,20", "--z2", "30,40", "--tol", "1e-3"]


def _files(root):
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def local(tmp_path_factory):
    out = tmp_path_factory.mktemp("atlas") / "a"
    assert main(ARGS + ["-o", str(out), "--workers", "2", "--no-progress"]) == 0
    return out


def test_dataset_is_queryable(local):
    index = json.loads((local / "index.json").read_text())
    assert [(c["z1"], c["z2"]) for c in index["cells"]] == [(12, 30), (12, 40), (20, 30), (20, 40)]
    assert not [p for p in local.rglob("*") if ".part" in p.name]
    assert (local / "atlas.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    row = next(c for c in index["cells"] if (c["z1"], c["z2"]) == (12, 40))
    cell = json.loads((local / row["file"]).read_text())
    assert cell["contour"]["pair"]["z1"] == 12 and not cell["contour"]["region"]["empty"]
    assert row["passes"] and check_pair(PairSpec(12, 40, 1.0, row["x1"], row["x2"])).ok


def test_deterministic_and_resumable(local, tmp_path, capsys, monkeypatch):
    """One worker writes the same bytes as two; a run that lost a cell (interrupted) computes only it."""
    again = tmp_path / "b"
    assert main(ARGS + ["-o", str(again), "--workers", "1", "--no-progress"]) == 0
    assert _files(again) == _files(local)
    (again / "cells" / "z1-020_z2-030.json").unlink()
    (again / "index.json").unlink()
    capsys.readouterr()
    from gearkit.progress import Progress

    monkeypatch.setattr(Progress, "delay", 0.0)  # draw at once (a bar waits half a second of work)
    assert main(["--progress"] + ARGS + ["-o", str(again)]) == 0
    assert "1/1 cells" in capsys.readouterr().err  # the progress bar: one cell left to compute
    assert _files(again) == _files(local)


def test_on_a_dask_cluster_the_same_files(local, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp",
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        out = tmp_path / "d"
        assert main(ARGS + ["-o", str(out), "--scheduler", cluster.scheduler_address, "--no-progress"]) == 0
    assert _files(out) == _files(local)


def test_bad_input_and_other_options(local, capsys):
    assert main(["atlas", "--z1", "10:5:0", "--z2", "30", "-o", str(local)]) == 2
    assert main(["atlas", "--z1", "12,20", "--z2", "2", "-o", str(local)]) == 2
    # the directory holds an atlas at another tolerance: refused, nothing overwritten
    before = _files(local)
    assert main(["atlas", "--z1", "12,20", "--z2", "30,40", "--tol", "1e-4", "-o", str(local)]) == 2
    assert "another template or options" in capsys.readouterr().err
    assert _files(local) == before


def test_internal_atlas_names_cells_that_are_no_pair(tmp_path):
    out = tmp_path / "ring"
    assert main(["atlas", "--z1", "20,50", "--z2", "49", "--internal", "--cutter-teeth", "20", "--tol", "1e-3",
                 "-o", str(out), "--no-progress", "--workers", "1"]) == 0
    rows = {(c["z1"], c["z2"]): c for c in json.loads((out / "index.json").read_text())["cells"]}
    assert rows[(50, 49)]["status"] == "error" and "teeth" in rows[(50, 49)]["error"]
    assert rows[(20, 49)]["status"] == "ok"



def test_contact_sheet_title_is_not_cut_off(local):
    """The 2 x 2 sheet is narrower than its title: the title is wrapped to the figure, so no ink
    touches the image's left or right edge (a cut-off title runs through both)."""
    from matplotlib.image import imread

    img = imread(local / "atlas.png")[..., :3]
    ink = img.min(axis=2) < 0.5  # dark pixels: text and outlines
    assert not ink[:, 0].any() and not ink[:, -1].any()
    assert ink[: img.shape[0] // 5].any()  # the title is there, at the top

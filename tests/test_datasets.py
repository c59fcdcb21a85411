"""Datasets as they ship: miniature OTB-100 and UAV123 trees with the real quirk tables."""
import cv2
import numpy as np
import pytest

from trackbook import clips
from trackbook.clips import _dataset_tables as T
from trackbook.clips.datasets import DatasetWarning, detect, load_dataset
from trackbook.evaluation import bench

_JPG = cv2.imencode(".jpg", np.full((24, 32, 3), 90, np.uint8))[1].tobytes()
_PNG = cv2.imencode(".png", np.full((24, 32, 3), 90, np.uint8))[1].tobytes()

# every quirk of the OTB-100 table: late start, early end, omitted first frames, 5-digit
# names, PNG, two targets, Human4's second file only
QUIRKS = ["David", "BlurCar1", "BlurCar3", "BlurCar4", "Football1", "Freeman3", "Freeman4",
          "Diving", "Tiger1", "Board", "KiteSurf", "Jogging.1", "Jogging.2", "Skating2.1",
          "Skating2.2", "Human4.2"]


def _gt(n, x0=4.0):
    return "\n".join(f"{x0 + i % 5},{5},{8},{6}" for i in range(n)) + "\n"


def _otb_tree(root):
    for name in QUIRKS:
        folder, a, b, nz, ext, anno, skip = T.OTB100[name]
        img = root / folder / "img"
        img.mkdir(parents=True, exist_ok=True)
        # as shipped: images beyond the annotated range (Football1 has 81 images, 74 boxes)
        for i in range(1, b + 8):
            (img / f"{i:0{nz}d}.{ext}").write_bytes(_PNG if ext == "png" else _JPG)
        (root / folder / anno).write_text(_gt(b - a + 1))
    (root / "Human4" / "groundtruth_rect.1.txt").write_text("")   # empty, as shipped
    return root


def test_every_otb_quirk_loads_with_the_toolkit_range(tmp_path):
    root = _otb_tree(tmp_path / "OTB100")
    assert detect(root) == "otb100"
    seqs = {s.name: s for s in load_dataset(root)}
    assert set(seqs) == set(QUIRKS)
    for name in QUIRKS:
        folder, a, b, nz, ext, anno, skip = T.OTB100[name]
        s = seqs[name]
        c = s.load()
        assert len(c) == b - a + 1 - skip, name
        assert c.groundtruth.shape == (len(c), 4)
        first = f"{a + skip:0{nz}d}.{ext}"
        assert c.frames.paths[0].name == first and c.frames.paths[-1].name == f"{b:0{nz}d}.{ext}"
    assert len(seqs["David"]) == 471 and seqs["David"].images[0].endswith("0300.jpg")
    assert len(seqs["Football1"]) == 74
    assert seqs["Board"].images[0].endswith("00001.jpg")
    assert seqs["Tiger1"].images[0].endswith("0006.jpg")
    assert seqs["Jogging.1"].groundtruth.endswith("groundtruth_rect.1.txt")
    assert seqs["Jogging.2"].groundtruth.endswith("groundtruth_rect.2.txt")
    assert "OCC" in seqs["Jogging.1"].attributes and "IV" in seqs["David"].attributes


def test_bench_on_a_dataset_root_lists_every_sequence_and_writes_attributes(tmp_path):
    root = tmp_path / "OTB100"
    for name in ("Jogging.1", "Jogging.2", "Football1"):
        folder, a, b, nz, ext, anno, skip = T.OTB100[name]
        img = root / folder / "img"
        img.mkdir(parents=True, exist_ok=True)
        rng = np.random.default_rng(len(name))
        for i in range(1, b + 8):
            f = rng.integers(0, 255, (60, 80, 3), dtype=np.uint8)
            cv2.imwrite(str(img / f"{i:0{nz}d}.{ext}"), f)
        (root / folder / anno).write_text(_gt(b - a + 1, x0=10 + 5 * (name == "Jogging.2")))
    rows = bench.run(["mean-shift"], str(root), tmp_path / "o", progress=False,
                     reference=False, max_frames=4)
    assert sorted(r["clip"] for r in rows) == ["Football1", "Jogging.1", "Jogging.2"]
    table = (tmp_path / "o" / "attributes.md").read_text()
    names = ("Jogging_1", "Jogging_2", "Football1")
    for a in T.OTB_ATTRIBUTE_NAMES:                      # counts follow the OTB table
        k = sum(a in T.OTB_ATTRIBUTES[n] for n in names)
        assert (f"| {a} | mean-shift | {k} |" in table) == (k > 0), a
    assert (tmp_path / "o" / "success_OPR.png").is_file()


def test_uav123_layout_with_frame_ranges_and_nan_rows(tmp_path):
    root = tmp_path / "UAV123"
    data = root / "data_seq" / "UAV123" / "bird1"
    anno = root / "anno" / "UAV123"
    data.mkdir(parents=True)
    anno.mkdir(parents=True)
    last = max(T.UAV123[n][2] for n in ("bird1_1", "bird1_2", "bird1_3"))
    for i in range(1, last + 1):
        (data / f"{i:06d}.jpg").write_bytes(_JPG)
    for n in ("bird1_1", "bird1_2", "bird1_3"):
        _, a, b, *_ = T.UAV123[n]
        rows = _gt(b - a + 1).splitlines()
        rows[3] = "NaN,NaN,NaN,NaN"                        # target out of view
        (anno / f"{n}.txt").write_text("\n".join(rows) + "\n")
    assert detect(root) == "uav123"
    seqs = {s.name: s for s in load_dataset(root)}
    assert set(seqs) == {"bird1_1", "bird1_2", "bird1_3"}
    c = seqs["bird1_2"].load()
    assert c.frames.paths[0].name == "000775.jpg" and len(c) == 1477 - 775 + 1
    assert np.isnan(c.groundtruth[3]).all() and np.isfinite(c.groundtruth[4]).all()
    assert "FOC" in seqs["bird1_1"].attributes


def test_plain_folder_of_sequences_keeps_working(tmp_path):
    root = tmp_path / "mine"
    for name in ("one", "two"):
        img = root / name / "img"
        img.mkdir(parents=True)
        for i in range(1, 6):
            (img / f"{i:04d}.jpg").write_bytes(_JPG)
        (root / name / "groundtruth.txt").write_text(_gt(5))
    assert detect(root) == "folders"
    assert [s.name for s in clips.load_dataset(root)] == ["one", "two"]
    assert len(clips.load_dataset(root)[0].load()) == 5


def test_wrong_range_names_the_file(tmp_path):
    root = _otb_tree(tmp_path / "OTB100")
    (root / "David" / "groundtruth_rect.txt").write_text(_gt(770))
    with pytest.warns(DatasetWarning, match="1 folder"):
        ds = load_dataset(root)
    assert "David" not in [x.name for x in ds]               # listed as skipped, with why
    assert [k.name for k in ds.skipped] == ["David"]
    assert "groundtruth_rect.txt has 770 boxes" in ds.skipped[0].reason
    with pytest.raises(ValueError, match="groundtruth_rect.txt has 770 boxes"):
        load_dataset(root, strict=True)
    with pytest.raises(ValueError, match="unknown dataset kind"):
        load_dataset(root, kind="otb")


def test_one_attribute_table_the_otb_toolkits():
    from trackbook.clips.datasets import attributes
    from trackbook.evaluation import compare

    # Crossing in the OTB toolkit's attribute list (Wu et al. 2015): SV DEF FM OPR BC
    assert set(attributes("Crossing")) == {"SV", "DEF", "FM", "OPR", "BC"}
    assert attributes("Jogging1") == attributes("Jogging.1") == T.OTB_ATTRIBUTES["Jogging_1"]
    assert attributes("Bag") == T.VOT_ATTRIBUTES["Bag"] and attributes("NoSuchSeq") == ()
    for name, codes in compare.SEQUENCE_ATTRIBUTES.items():   # the guide reads the same table
        assert codes == (T.OTB_ATTRIBUTES.get(name.replace("1", "_1") if name == "Jogging1"
                                              else name) or T.VOT_ATTRIBUTES[name]), name

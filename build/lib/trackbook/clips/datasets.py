"""Benchmarks loaded as they ship: OTB-100, UAV123, or any folder of OTB-style sequences.

``load_dataset(root)`` lists the sequences of a downloaded benchmark as :class:`Sequence`
objects (cheap: nothing is decoded until ``.load()``), each with the frame range, target and
attributes the benchmark's own toolkit uses. The facts come from the toolkits' tables in
:mod:`trackbook.clips._dataset_tables` (source cited there); the quirks they encode:

- OTB-100: ground truth starting after image 1 (David images 300-770, BlurCar1 247-988,
  BlurCar3 3-359, BlurCar4 18-397) or ending before the last image (Football1 1-74,
  Freeman3 1-460, Freeman4 1-283, Diving 1-215); Tiger1's first 5 frames omitted (the
  toolkit's ``initOmit``); five-digit image names (Board); PNG images (KiteSurf); two targets
  (``groundtruth_rect.1.txt``/``.2.txt``: ``Jogging.1``, ``Jogging.2``, ``Skating2.1``,
  ``Skating2.2``) and Human4, whose usable file is ``.2`` (``Human4.2``).
- UAV123: images in ``data_seq/UAV123/<video>/000001.jpg`` and annotations in
  ``anno/UAV123/<sequence>.txt``; several sequences cut from one video by frame ranges
  (``bird1_1`` = images 1-253, ``bird1_2`` = 775-1477, ...); ``NaN`` rows while the target is
  out of view (kept as unknown: they are not scored).

Sequence folders the table does not know (and plain folders of OTB-style sequences) load as
:func:`trackbook.clips.load_folder` would: every image, one box per image.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from . import _dataset_tables as _t
from .clip import Clip, ImageFiles
from .loaders import GT_NAMES, IMAGE_SUFFIXES, read_groundtruth

KINDS = ("auto", "otb100", "uav123", "folders")


@dataclasses.dataclass(frozen=True)
class Sequence:
    """One sequence of a dataset: an explicit image list and its ground-truth file.

    ``skip`` ground-truth rows are dropped first (OTB's Tiger1). ``identity`` (the resolved
    image folder and annotation file) tells two sequences apart in a benchmark.
    """

    name: str
    images: tuple
    groundtruth: str
    skip: int = 0
    attributes: tuple = ()
    fps: float = 30.0

    @property
    def identity(self) -> str:
        first = Path(self.images[0]).resolve() if self.images else Path("?")
        return f"{first.parent}[{Path(self.images[0]).name}..{Path(self.images[-1]).name}]" \
               f"#{Path(self.groundtruth).resolve()}"

    def __len__(self) -> int:
        return len(self.images)

    def load(self) -> Clip:
        """The clip: images read on access, ground truth checked against the image count."""
        missing = [p for p in (self.images[0], self.images[-1]) if not Path(p).is_file()]
        if missing:
            raise FileNotFoundError(
                f"sequence {self.name!r}: image {missing[0]} does not exist; the dataset's "
                "table expects it (is the download complete?).")
        gt = read_groundtruth(self.groundtruth)[self.skip:]
        if gt.shape[0] != len(self.images):
            raise ValueError(
                f"{self.groundtruth} has {gt.shape[0]} boxes (after skipping {self.skip}) but "
                f"sequence {self.name!r} has {len(self.images)} images "
                f"({Path(self.images[0]).name} .. {Path(self.images[-1]).name}); the file does "
                "not belong to this frame range.")
        return Clip(self.name, ImageFiles(self.images), gt, fps=self.fps,
                    attributes=tuple(self.attributes), source=str(Path(self.images[0]).parent))


def _img_dir(folder: Path) -> Path:
    return folder / "img" if (folder / "img").is_dir() else folder


def _images(folder: Path) -> list[Path]:
    d = _img_dir(folder)
    if not d.is_dir():
        return []
    return sorted(p for p in d.iterdir() if p.suffix.lower() in IMAGE_SUFFIXES)


def _gt_files(folder: Path) -> list[Path]:
    for n in GT_NAMES:
        if (folder / n).is_file():
            return [folder / n]
    return sorted(f for f in folder.glob("groundtruth_rect.*.txt")
                  if f.stat().st_size > 0)          # OTB's Human4 ships an empty .1


def _uav_roots(root: Path):
    for base in (root, root.parent):
        d, a = base / "data_seq" / "UAV123", base / "anno" / "UAV123"
        if d.is_dir() and a.is_dir():
            return d, a
    return None


def is_sequence(folder: Path) -> bool:
    """A folder holding one sequence (images, or ``img/``, and a ground-truth file)."""
    return bool(_gt_files(folder)) and bool(_images(folder))


def is_dataset(root) -> bool:
    """A folder of sequences (OTB-style sub-folders) or a UAV123 tree, not one sequence."""
    root = Path(root)
    if not root.is_dir() or is_sequence(root):
        return False
    if _uav_roots(root):
        return True
    return any(is_sequence(d) for d in root.iterdir() if d.is_dir())


def _otb_attributes(name: str, folder: str) -> tuple:
    for k in (name, name.replace(".", "_"), folder):
        if k in _t.OTB_ATTRIBUTES:
            return tuple(_t.OTB_ATTRIBUTES[k])
    return ()


def _plain(folder: Path, attributes=()) -> list[Sequence]:
    imgs = tuple(str(p) for p in _images(folder))
    gts = _gt_files(folder)
    if not imgs or not gts:
        return []
    if len(gts) == 1:
        return [Sequence(folder.name, imgs, str(gts[0]), attributes=tuple(attributes))]
    return [Sequence(f"{folder.name}.{g.name.split('.')[1]}", imgs, str(g),
                     attributes=tuple(attributes)) for g in gts]


def _otb(root: Path) -> list[Sequence]:
    out, known = [], set()
    for name, (folder, a, b, nz, ext, anno, skip) in _t.OTB100.items():
        d = root / folder
        imgs = tuple(str(_img_dir(d) / f"{i:0{nz}d}.{ext}") for i in range(a + skip, b + 1))
        if not ((d / anno).is_file() and Path(imgs[0]).is_file() and Path(imgs[-1]).is_file()):
            continue  # not as shipped (e.g. already trimmed): loaded as a plain folder below
        known.add(folder)
        out.append(Sequence(name, imgs, str(d / anno), skip=skip,
                            attributes=_otb_attributes(name, folder)))
    for d in sorted(p for p in root.iterdir() if p.is_dir() and p.name not in known):
        out.extend(_plain(d, _otb_attributes(d.name, d.name)))
    return out


def _uav(root: Path) -> list[Sequence]:
    data, anno = _uav_roots(root)
    out = []
    for name, (video, a, b, nz, ext, ann) in _t.UAV123.items():
        if not (data / video).is_dir():
            continue
        imgs = tuple(str(data / video / f"{i:0{nz}d}.{ext}") for i in range(a, b + 1))
        out.append(Sequence(name, imgs, str(anno / ann),
                            attributes=tuple(_t.UAV_ATTRIBUTES.get(name, ()))))
    return out


def _folders(root: Path) -> list[Sequence]:
    out = []
    for d in sorted(p for p in root.iterdir() if p.is_dir()):
        out.extend(_plain(d))
    return out


def detect(root) -> str:
    """``"uav123"``, ``"otb100"`` (a sub-folder named as in OTB-100's table) or ``"folders"``."""
    root = Path(root)
    if _uav_roots(root):
        return "uav123"
    folders = {v[0] for v in _t.OTB100.values()}
    if any((root / f).is_dir() for f in folders):
        return "otb100"
    return "folders"


def load_dataset(root, kind: str = "auto") -> list[Sequence]:
    """Every sequence of a benchmark folder, as the benchmark's toolkit defines it.

    Parameters
    ----------
    root : path of the dataset (``.../OTB100`` holding ``Basketball/``, ``Jogging/`` ...;
        ``.../UAV123`` holding ``data_seq/`` and ``anno/``; or any folder of OTB-style
        sequence folders)
    kind : ``"auto"`` (detect), ``"otb100"``, ``"uav123"`` or ``"folders"``

    Returns
    -------
    list of :class:`Sequence`, in the table's order; call ``.load()`` for a
    :class:`~trackbook.clips.Clip`, or pass the list to ``bench.run(clips=...)``.
    """
    root = Path(root).expanduser()
    if kind not in KINDS:
        raise ValueError(f"unknown dataset kind {kind!r}; use one of {', '.join(KINDS)}.")
    if not root.is_dir():
        raise FileNotFoundError(f"dataset folder {root} does not exist.")
    if kind == "auto":
        kind = detect(root)
    if kind == "uav123" and not _uav_roots(root):
        raise FileNotFoundError(f"{root} is not a UAV123 tree: expected data_seq/UAV123/ and "
                                "anno/UAV123/ in it.")
    seqs = {"otb100": _otb, "uav123": _uav, "folders": _folders}[kind](root)
    if not seqs:
        raise FileNotFoundError(
            f"no sequences in {root}; a dataset folder holds sequence folders "
            "(img/0001.jpg ... and groundtruth_rect.txt) or UAV123's data_seq/ and anno/.")
    return seqs


__all__ = ["Sequence", "load_dataset", "is_dataset", "detect", "KINDS"]

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

Nothing is dropped without a word: a folder (or a table entry whose folder is there) that
cannot be loaded -- no images, no ground truth, a dangling link, a box count that does not
match the images, a UAV123 video the table does not know -- is listed in the returned
:class:`Dataset`'s ``skipped`` with the reason, and a :class:`DatasetWarning` says how many;
``strict=True`` raises instead.
"""

from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path
from typing import NamedTuple


from .._checks import check_file, fs_error, list_dir
from . import _dataset_tables as _t
from .clip import Clip, ImageFiles
from .loaders import GT_NAMES, IMAGE_SUFFIXES, read_groundtruth


class DatasetWarning(UserWarning):
    """Some folders of a dataset could not be loaded (see ``Dataset.skipped``)."""


class Skipped(NamedTuple):
    """A folder or table entry :func:`load_dataset` could not load, and why."""

    name: str
    path: str
    reason: str


class Dataset(list):
    """The sequences of a dataset (a ``list`` of :class:`Sequence`), with ``root``, ``kind``
    and ``skipped``: every folder or table entry that could not be loaded, as
    :class:`Skipped` ``(name, path, reason)``."""

    def __init__(self, seqs=(), root: str = "", kind: str = "", skipped=()):
        super().__init__(seqs)
        self.root, self.kind, self.skipped = root, kind, list(skipped)

    def skipped_text(self) -> str:
        """One line: how many folders were skipped and why (the first few)."""
        if not self.skipped:
            return ""
        why = "; ".join(f"{s.name}: {s.reason}" for s in self.skipped[:3])
        more = f"; and {len(self.skipped) - 3} more" if len(self.skipped) > 3 else ""
        return (f"{len(self.skipped)} folder(s) of {self.root} skipped ({why}{more}); "
                f"{len(self)} sequence(s) loaded.")

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
        if not self.images:
            raise ValueError(f"sequence {self.name!r} has no images.")
        for p in (self.images[0], self.images[-1]):
            check_file(p, what=f"sequence {self.name!r}: image",
                       fix="the dataset's table expects it (is the download complete?).")
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
    return sorted(p for p in list_dir(d, what="image folder")
                  if p.suffix.lower() in IMAGE_SUFFIXES)


def _gt_files(folder: Path) -> list[Path]:
    for n in GT_NAMES:
        # a dangling link is found too: loading it says what is wrong instead of "no file"
        if (folder / n).is_file() or (folder / n).is_symlink():
            return [folder / n]
    try:
        return sorted(f for f in folder.glob("groundtruth_rect.*.txt")
                      if f.is_symlink() or f.stat().st_size > 0)  # Human4 ships an empty .1
    except OSError as e:
        raise fs_error(e, folder, "sequence folder") from None


def _problem(seq: Sequence) -> str | None:
    """Why ``seq`` cannot be loaded (what :meth:`Sequence.load` would raise), or None."""
    try:
        seq.load()
    except (ValueError, OSError) as e:
        return str(e)
    return None


def _uav_roots(root: Path):
    for base in (root, root.parent):
        d, a = base / "data_seq" / "UAV123", base / "anno" / "UAV123"
        if d.is_dir() and a.is_dir():
            return d, a
    return None


def is_sequence(folder: Path) -> bool:
    """A folder holding one sequence (images, or ``img/``, and a ground-truth file)."""
    try:
        return bool(_gt_files(folder)) and bool(_images(folder))
    except (OSError, ValueError):      # unreadable: not a sequence, as far as we can tell
        return False


def is_dataset(root) -> bool:
    """A folder of sequences (OTB-style sub-folders) or a UAV123 tree, not one sequence."""
    root = Path(root)
    if not root.is_dir() or is_sequence(root):
        return False
    if _uav_roots(root):
        return True
    return any(is_sequence(d) for d in list_dir(root, what="dataset folder") if d.is_dir())


def holds_folders(root) -> bool:
    """A folder with sub-folders and no images of its own: meant as a folder of sequences
    even when none of them loads, so :func:`load_dataset` can say what each one lacks."""
    root = Path(root)
    try:
        return (root.is_dir() and not _images(root) and not _gt_files(root)
                and any(d.is_dir() and d.name != "img"
                        for d in list_dir(root, what="dataset folder")))
    except (OSError, ValueError):
        return False


def _otb_attributes(name: str, folder: str) -> tuple:
    for k in (name, name.replace(".", "_"), folder):
        if k in _t.OTB_ATTRIBUTES:
            return tuple(_t.OTB_ATTRIBUTES[k])
    return ()


def attributes(name: str) -> tuple:
    """OTB attribute codes of a sequence, by its OTB or folder name (``()`` if unknown).

    The OTB toolkit's table (``_dataset_tables.OTB_ATTRIBUTES``; a second target of a
    sequence is spelt ``Jogging.1``, ``Jogging_1`` or, as a folder, ``Jogging1``), then the
    two VOT sequences of the development set (``_dataset_tables.VOT_ATTRIBUTES``).
    """
    found = _otb_attributes(name, name)
    if not found and name[-1:].isdigit() and name[-2:-1].isalpha():
        found = _otb_attributes(f"{name[:-1]}_{name[-1]}", name)
    return found or tuple(_t.VOT_ATTRIBUTES.get(name, ()))


def _plain(folder: Path, attributes=(), skipped=None) -> list[Sequence]:
    """The sequences of one OTB-style folder; why none, appended to ``skipped``."""
    def skip(reason):
        if skipped is not None:
            skipped.append(Skipped(folder.name, str(folder), reason))
        return []
    try:
        imgs = tuple(str(p) for p in _images(folder))
        gts = _gt_files(folder)
    except (OSError, ValueError) as e:
        return skip(str(e))
    if not imgs:
        return skip(f"no images (.jpg, .png, .bmp) in {folder} or its img/ folder")
    if not gts:
        return skip(f"no ground truth ({', '.join(GT_NAMES)} or groundtruth_rect.N.txt) "
                    f"in {folder}")
    if len(gts) == 1:
        seqs = [Sequence(folder.name, imgs, str(gts[0]), attributes=tuple(attributes))]
    else:
        seqs = [Sequence(f"{folder.name}.{g.name.split('.')[1]}", imgs, str(g),
                         attributes=tuple(attributes)) for g in gts]
    out = []
    for q in seqs:
        why = _problem(q)
        if why is None:
            out.append(q)
        elif skipped is not None:
            skipped.append(Skipped(q.name, str(folder), why))
    return out


def _otb(root: Path, skipped: list) -> list[Sequence]:
    out, known, pending = [], set(), {}
    for name, (folder, a, b, nz, ext, anno, skip) in _t.OTB100.items():
        d = root / folder
        if not d.is_dir():
            continue           # not downloaded: not part of this dataset
        imgs = tuple(str(_img_dir(d) / f"{i:0{nz}d}.{ext}") for i in range(a + skip, b + 1))
        q = Sequence(name, imgs, str(d / anno), skip=skip,
                     attributes=_otb_attributes(name, folder))
        why = _problem(q)
        if why is not None:    # not as shipped (e.g. already trimmed): tried as a plain folder
            pending.setdefault(folder, []).append(Skipped(name, str(d), why))
            continue
        known.add(folder)
        out.append(q)
    for folder, entries in pending.items():   # Jogging.1 loaded but Jogging.2 could not
        if folder in known:
            skipped.extend(entries)
    for d in sorted(p for p in list_dir(root, what="dataset folder")
                    if p.is_dir() and p.name not in known):
        mine: list[Skipped] = []
        got = _plain(d, _otb_attributes(d.name, d.name), mine)
        out.extend(got)
        # a folder the table knows that loads neither way: the table's reason says more
        skipped.extend(pending[d.name] if not got and d.name in pending else mine)
    return out


def _uav(root: Path, skipped: list) -> list[Sequence]:
    data, anno = _uav_roots(root)
    out, videos = [], set()
    for name, (video, a, b, nz, ext, ann) in _t.UAV123.items():
        videos.add(video)
        if not (data / video).is_dir():
            continue
        imgs = tuple(str(data / video / f"{i:0{nz}d}.{ext}") for i in range(a, b + 1))
        q = Sequence(name, imgs, str(anno / ann),
                     attributes=tuple(_t.UAV_ATTRIBUTES.get(name, ())))
        has_imgs = Path(imgs[0]).is_file() or Path(imgs[-1]).is_file()
        has_anno = (anno / ann).is_file() or (anno / ann).is_symlink()
        if not (has_imgs or has_anno):
            continue           # a sub-sequence not downloaded (bird1_2 when only bird1_1 is)
        why = _problem(q)
        if why is None:
            out.append(q)
        else:
            skipped.append(Skipped(name, str(data / video), why))
    for d in sorted(p for p in list_dir(data, what="UAV123 image folder")
                    if p.is_dir() and p.name not in videos):
        ann = anno / f"{d.name}.txt"
        if not ann.exists():
            skipped.append(Skipped(d.name, str(d), f"a video UAV123's table does not list, "
                                   f"and no annotation {ann}"))
            continue
        q = Sequence(d.name, tuple(str(p) for p in _images(d)), str(ann))
        why = _problem(q) if len(q) else f"no images in {d}"
        if why is None:
            out.append(q)
        else:
            skipped.append(Skipped(d.name, str(d), why))
    return out


def _folders(root: Path, skipped: list) -> list[Sequence]:
    out = []
    for d in sorted(p for p in list_dir(root, what="dataset folder") if p.is_dir()):
        out.extend(_plain(d, skipped=skipped))
    return out


def _once(seqs, skipped: list) -> list[Sequence]:
    """Each sequence once: a second folder that leads to the same images and ground truth
    (a link to another sequence's folder) would count that sequence twice in every mean, so
    it is listed in ``skipped`` with the name it duplicates, not dropped without a word."""
    first: dict = {}
    out = []
    for q in seqs:
        other = first.setdefault(q.identity, q)
        if other is q:
            out.append(q)
        else:
            folder = Path(q.images[0]).parent
            skipped.append(Skipped(q.name, str(folder), f"the same sequence as {other.name} "
                                   f"(both lead to {folder.resolve()}); benched once, as "
                                   f"{other.name}"))
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


def load_dataset(root, kind: str = "auto", strict: bool = False) -> Dataset:
    """Every sequence of a benchmark folder, as the benchmark's toolkit defines it.

    Parameters
    ----------
    root : path of the dataset (``.../OTB100`` holding ``Basketball/``, ``Jogging/`` ...;
        ``.../UAV123`` holding ``data_seq/`` and ``anno/``; or any folder of OTB-style
        sequence folders)
    kind : ``"auto"`` (detect), ``"otb100"``, ``"uav123"`` or ``"folders"``
    strict : raise ``ValueError`` listing the folders that cannot be loaded, instead of
        skipping them with a :class:`DatasetWarning`

    Returns
    -------
    :class:`Dataset`, a list of :class:`Sequence` in the table's order (call ``.load()`` for
    a :class:`~trackbook.clips.Clip`, or pass it to ``bench.run(clips=...)``); its ``skipped``
    lists every folder or table entry that could not be loaded, with the reason. Every
    sequence listed has been checked to load (images at both ends of its range, ground truth
    readable, one box per image).
    """
    root = Path(root).expanduser()
    if kind not in KINDS:
        raise ValueError(f"unknown dataset kind {kind!r}; use one of {', '.join(KINDS)}.")
    try:
        root.stat()
    except OSError as e:
        raise fs_error(e, root, "dataset folder") from None
    if not root.is_dir():
        raise FileNotFoundError(f"dataset folder {root} does not exist (or is not a folder).")
    if kind == "auto":
        kind = detect(root)
    if kind == "uav123" and not _uav_roots(root):
        raise FileNotFoundError(f"{root} is not a UAV123 tree: expected data_seq/UAV123/ and "
                                "anno/UAV123/ in it.")
    skipped: list[Skipped] = []
    found = {"otb100": _otb, "uav123": _uav, "folders": _folders}[kind](root, skipped)
    seqs = Dataset(_once(found, skipped), root=str(root), kind=kind, skipped=skipped)
    if skipped and (strict or not seqs):
        raise ValueError(f"dataset {root}: " + (seqs.skipped_text() if strict else
                         f"no sequence could be loaded; {seqs.skipped_text()}")
                         + (" Fix or remove those folders, or pass strict=False to skip them."
                            if strict else ""))
    if not seqs:
        raise FileNotFoundError(
            f"no sequences in {root}; a dataset folder holds sequence folders "
            "(img/0001.jpg ... and groundtruth_rect.txt) or UAV123's data_seq/ and anno/.")
    if skipped:
        warnings.warn(seqs.skipped_text(), DatasetWarning, stacklevel=2)
    return seqs


__all__ = ["Sequence", "Dataset", "Skipped", "DatasetWarning", "load_dataset",
           "is_dataset", "holds_folders", "detect", "KINDS"]

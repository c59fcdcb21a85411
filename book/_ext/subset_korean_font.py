"""Make the book's Korean font: Noto Sans KR cut down to the Korean characters the book shows.

The popovers of the ``{quote}`` role show passages of four Korean papers as printed, and a few
pages quote Korean words; a reader whose system has no Korean font would see empty boxes. The
book therefore ships ``_static/fonts/noto-sans-kr-subset.woff``: Noto Sans KR (SIL Open Font
License 1.1, ``_static/fonts/OFL.txt``) holding only the glyphs of every Hangul, CJK and CJK
punctuation character (and circled digit) found in the quote register
(``src/trackbook/quotes/*.py``) and in the book's pages (``book/*.md``).
``_static/korean-font.css`` declares it with a ``unicode-range`` of those blocks, so Latin text
keeps the theme's font (and the font holds no Latin unless ``--latin`` asks for it).
``tests/test_korean_font.py`` fails when a page or a quote brings a character the font lacks:
run this script again then, and commit the font.

The source is the ``@fontsource/noto-sans-kr`` package of the npm registry (Google Fonts'
Noto Sans KR, version 2.004, cut into slices of ``unicode-range``; the weight 400 slices are
used). fontTools is needed to run the script, nothing else of the book needs it::

    npm pack @fontsource/noto-sans-kr@5.3.0         # fontsource-noto-sans-kr-5.3.0.tgz
    python -m venv /tmp/fontvenv && /tmp/fontvenv/bin/pip install fonttools
    /tmp/fontvenv/bin/python book/_ext/subset_korean_font.py fontsource-noto-sans-kr-5.3.0.tgz

The output is the same, byte for byte, for the same source and the same pages (no time stamp
is written).
"""

from __future__ import annotations

import argparse
import io
import json
import re
import sys
import tarfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FONT = ROOT / "_static" / "fonts" / "noto-sans-kr-subset.woff"
LICENCE = ROOT / "_static" / "fonts" / "OFL.txt"

#: The blocks whose characters the font must hold (inclusive code point ranges): Hangul
#: Jamo, circled and parenthesised digits (numbering in Korean papers), CJK Symbols and
#: Punctuation (「」〈〉 and the like), Hangul Compatibility Jamo, Enclosed CJK Letters,
#: CJK Unified Ideographs and Extension A (Hanja), Hangul Jamo Extended-A, Hangul Syllables
#: with Jamo Extended-B, CJK Compatibility Ideographs, Halfwidth and Fullwidth Forms. The same
#: ranges are the ``unicode-range`` of ``_static/korean-font.css``.
KOREAN = ((0x1100, 0x11FF), (0x2460, 0x24FF), (0x3000, 0x303F), (0x3130, 0x318F),
          (0x3200, 0x32FF), (0x3400, 0x4DBF), (0x4E00, 0x9FFF), (0xA960, 0xA97F),
          (0xAC00, 0xD7FF), (0xF900, 0xFAFF), (0xFF00, 0xFFEF))
#: Basic Latin, printable (``--latin``: for other uses of the file; the unicode-range of the
#: book's CSS leaves Latin to the theme's font)
LATIN = range(0x20, 0x7F)
#: the weight the book uses
WEIGHT = 400


def is_korean(ch: str) -> bool:
    """Whether ``ch`` lies in one of the :data:`KOREAN` blocks."""
    o = ord(ch)
    return any(lo <= o <= hi for lo, hi in KOREAN)


def book_characters(root: Path = ROOT) -> set[str]:
    """Every Korean character of the quote register's modules and the book's pages."""
    files = sorted((root / "src" / "trackbook" / "quotes").glob("*.py")) + \
        sorted((root / "book").glob("*.md"))
    return {ch for f in files for ch in f.read_text(encoding="utf-8") if is_korean(ch)}


def _slices(source: Path) -> dict[str, bytes]:
    """The weight-400 WOFF slices of the npm package (a ``.tgz`` or its unpacked folder), by
    slice name (``korean``, ``latin``, ``0`` … ``119``)."""
    pattern = re.compile(rf"files/noto-sans-kr-([a-z0-9]+)-{WEIGHT}-normal\.woff$")
    out = {}
    if source.is_dir():
        for f in source.rglob("*.woff"):
            m = pattern.search(f.as_posix())
            if m:
                out[m.group(1)] = f.read_bytes()
    else:
        with tarfile.open(source) as tar:
            for member in tar.getmembers():
                m = pattern.search(member.name)
                if m:
                    out[m.group(1)] = tar.extractfile(member).read()
    if "korean" not in out:
        raise SystemExit(f"{source}: no noto-sans-kr-korean-{WEIGHT}-normal.woff; give the "
                         f"@fontsource/noto-sans-kr package")
    return out


def _package_file(source: Path, name: str) -> str:
    """The text of the package's top-level file ``name`` (``LICENSE``, ``package.json``)."""
    if source.is_dir():
        top = source / "package" if (source / "package").is_dir() else source
        return (top / name).read_text(encoding="utf-8")
    with tarfile.open(source) as tar:
        return tar.extractfile(f"package/{name}").read().decode("utf-8")


def licence(source: Path, font) -> str:
    """``OFL.txt``: where the file comes from, the font's copyright notice and the package's
    licence text as shipped."""
    version = json.loads(_package_file(source, "package.json"))["version"]
    notice = font["name"].getDebugName(0)
    return (f"noto-sans-kr-subset.woff: Noto Sans KR (weight 400), cut down to the Korean "
            f"characters of this book\nby book/_ext/subset_korean_font.py from the npm package "
            f"@fontsource/noto-sans-kr {version}.\nCopyright notice in the font: {notice}\n\n"
            + _package_file(source, "LICENSE"))


def _subset(data: bytes, codepoints: set[int]):
    from fontTools import subset

    options = subset.Options()
    options.layout_features = ["kern", "vert", "vrt2"]   # nothing else applies to these glyphs
    options.hinting = False             # hinting instructions outweigh the outlines at this size
    options.name_IDs = [0, 1, 2, 3, 4, 5, 6, 13, 14]     # keep the copyright and licence lines
    options.notdef_outline = True
    font = subset.load_font(io.BytesIO(data), options)
    sub = subset.Subsetter(options)
    sub.populate(unicodes=codepoints)
    sub.subset(font)
    return font


def build(source: Path, chars: set[str], latin: bool = False):
    """The subset font (a fontTools ``TTFont``, WOFF flavour) holding ``chars`` (and, with
    ``latin``, basic Latin): the ``korean`` slice's glyphs, then each other slice's glyphs
    for what it lacks."""
    from fontTools.ttLib import TTFont

    slices = _slices(source)
    want = {ord(c) for c in chars} | (set(LATIN) if latin else set())
    cmaps = {}
    for name, data in slices.items():
        cmaps[name] = set(TTFont(io.BytesIO(data), lazy=True).getBestCmap())
    order = ["korean", "latin"] + sorted((n for n in slices if n.isdigit()), key=int)
    plan, left = {}, set(want)
    for name in order:
        take = left & cmaps.get(name, set())
        if take:
            plan[name], left = take, left - take
    if left:
        raise SystemExit("Noto Sans KR has no glyph for " +
                         " ".join(f"U+{c:04X} {chr(c)}" for c in sorted(left)))
    base = _subset(slices["korean"], plan.pop("korean"))
    for name, take in plan.items():
        _add(base, _subset(slices[name], take))
    # the korean slice is fontsource's instance of the variable font at weight 400, whose names
    # still read "Thin"
    for rec in base["name"].names:
        if rec.nameID in (1, 3, 4, 6):
            rec.string = re.sub(r" ?Thin", "", rec.toUnicode())
    base.flavor = "woff"
    base.recalcBBoxes = True          # the bounding boxes and maxima over the merged glyphs
    return base


def _add(base, other):
    """Copy ``other``'s glyphs (outlines, metrics, cmap entries) that ``base`` lacks into it.

    The slices are cut from one font and share its glyph names, so a name means the same
    glyph in each."""
    have = set(base.getGlyphOrder())
    new = [g for g in other.getGlyphOrder() if g not in have]
    glyf, oglyf = base["glyf"], other["glyf"]
    for g in new:
        glyph = oglyf[g]
        glyph.expand(oglyf)           # keep the outline, not bytes tied to the other font
        glyf[g] = glyph
        base["hmtx"][g] = other["hmtx"][g]
        if "vmtx" in base and "vmtx" in other:
            base["vmtx"][g] = other["vmtx"][g]
    # setting a glyph of ``glyf`` may already have appended its name to the order: once each
    base.setGlyphOrder(list(dict.fromkeys(base.getGlyphOrder() + new)))
    extra = other.getBestCmap()
    for table in base["cmap"].tables:
        if table.isUnicode():
            for cp, g in extra.items():
                if table.format == 4 and cp > 0xFFFF:
                    continue
                table.cmap.setdefault(cp, g)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("source", type=Path,
                        help="the @fontsource/noto-sans-kr package: its .tgz (npm pack) or folder")
    parser.add_argument("--latin", action="store_true",
                        help="also basic Latin (about 7 kB; the book's pages never use it)")
    parser.add_argument("--out", type=Path, default=FONT)
    args = parser.parse_args(argv)
    chars = book_characters()
    font = build(args.source, chars, latin=args.latin)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    buf = io.BytesIO()
    font.save(buf, reorderTables=True)
    args.out.write_bytes(buf.getvalue())
    if args.out == FONT:
        LICENCE.write_text(licence(args.source, font), encoding="utf-8")
    print(f"{args.out}: {len(chars)} Korean characters, {len(font.getGlyphOrder())} glyphs, "
          f"{args.out.stat().st_size} bytes")


if __name__ == "__main__":
    sys.exit(main())

"""The Korean font shipped with the book (``_static/fonts/noto-sans-kr-subset.woff``).

The quote popovers show passages of four Korean papers as printed, and a few pages quote Korean
words; the book ships Noto Sans KR cut down to those characters (``book/_ext/
subset_korean_font.py``) so that a reader without a Korean system font reads them. Checked here:

* every Korean character of the quote register and of the book's pages has a glyph with an
  outline in the committed font: its WOFF is read with the standard library only (the table
  directory, zlib, ``cmap`` formats 4 and 12, ``loca``), so a quote or a page that brings a
  new syllable fails until the font is made again; the reader is checked on a WOFF made by
  hand here;
* ``_static/korean-font.css`` declares the face with a URL relative to itself and a
  ``unicode-range`` covering those characters, the OFL licence lies beside the font;
* in headless Chromium, on a one-page book built with the book's theme and ``_static`` (from
  ``file://`` and over http): the popover's Korean passage and Korean in the page's text are
  drawn with the shipped face, fetched from the book's ``_static/fonts``, and its Latin text
  with the theme's font. ``tests/test_browser.py`` checks the same on the built book.
"""

from __future__ import annotations

import re
import struct
import zlib
from pathlib import Path

import pytest

from trackbook import quotes

from ._book_pages import FONT_FACE, KOREAN_BLOCKS, font_check, is_korean, serve
from ._playground_browser import CHROMIUM

ROOT = Path(__file__).resolve().parents[1]
FONT = ROOT / "_static" / "fonts" / "noto-sans-kr-subset.woff"
CSS = ROOT / "_static" / "korean-font.css"


# ---- reading a WOFF with the standard library ------------------------------------------------

def woff_tables(data: bytes) -> dict[str, bytes]:
    """The tables of a WOFF 1.0 font, each decompressed (zlib) where stored compressed."""
    sig, _flavor, length, n = struct.unpack(">4sIIH", data[:14])
    assert sig == b"wOFF", f"not a WOFF 1.0 file: {sig!r}"
    assert length == len(data), "the header's length is not the file's"
    tables = {}
    for i in range(n):
        tag, off, comp, orig, _ = struct.unpack(">4sIIII", data[44 + 20 * i:64 + 20 * i])
        raw = data[off:off + comp]
        tables[tag.decode("latin-1")] = zlib.decompress(raw) if comp < orig else raw
        assert len(tables[tag.decode("latin-1")]) == orig
    return tables


def _format4(t: bytes) -> dict[int, int]:
    seg2 = struct.unpack(">H", t[6:8])[0]
    n = seg2 // 2
    ends = struct.unpack(f">{n}H", t[14:14 + seg2])
    starts = struct.unpack(f">{n}H", t[16 + seg2:16 + 2 * seg2])
    deltas = struct.unpack(f">{n}h", t[16 + 2 * seg2:16 + 3 * seg2])
    ro_at = 16 + 3 * seg2                         # where the idRangeOffset array starts
    ranges = struct.unpack(f">{n}H", t[ro_at:ro_at + seg2])
    out = {}
    for i, (s, e, d, r) in enumerate(zip(starts, ends, deltas, ranges)):
        for c in range(s, e + 1):
            if c == 0xFFFF:
                continue
            if r == 0:
                g = (c + d) & 0xFFFF
            else:                                 # an offset from this idRangeOffset entry
                at = ro_at + 2 * i + r + 2 * (c - s)
                g = struct.unpack(">H", t[at:at + 2])[0]
                g = (g + d) & 0xFFFF if g else 0
            if g:
                out[c] = g
    return out


def _format12(t: bytes) -> dict[int, int]:
    n = struct.unpack(">I", t[12:16])[0]
    out = {}
    for k in range(n):
        s, e, g = struct.unpack(">III", t[16 + 12 * k:28 + 12 * k])
        out.update({c: g + c - s for c in range(s, e + 1)})
    return out


def cmap(tables: dict[str, bytes]) -> dict[int, int]:
    """Code point -> glyph index, from every Unicode subtable of format 4 or 12."""
    t = tables["cmap"]
    out = {}
    for k in range(struct.unpack(">H", t[2:4])[0]):
        platform, encoding, off = struct.unpack(">HHI", t[4 + 8 * k:12 + 8 * k])
        if not (platform == 0 or (platform == 3 and encoding in (1, 10))):
            continue
        fmt = struct.unpack(">H", t[off:off + 2])[0]
        if fmt == 4:
            out.update(_format4(t[off:off + struct.unpack(">H", t[off + 2:off + 4])[0]]))
        elif fmt == 12:
            out.update(_format12(t[off:off + struct.unpack(">I", t[off + 4:off + 8])[0]]))
    return out


def outline_bytes(tables: dict[str, bytes], glyph: int) -> int:
    """How many bytes of ``glyf`` the glyph's outline takes (0: nothing drawn)."""
    long = struct.unpack(">h", tables["head"][50:52])[0] == 1     # indexToLocFormat
    n = struct.unpack(">H", tables["maxp"][4:6])[0]
    loca = (struct.unpack(f">{n + 1}I", tables["loca"][:4 * (n + 1)]) if long else
            [2 * v for v in struct.unpack(f">{n + 1}H", tables["loca"][:2 * (n + 1)])])
    return loca[glyph + 1] - loca[glyph]


def missing(data: bytes, chars) -> list[str]:
    """The characters of ``chars`` the font ``data`` does not draw (no cmap entry, or a glyph
    without an outline)."""
    tables = woff_tables(data)
    cm = cmap(tables)
    return sorted(c for c in set(chars) if ord(c) not in cm or not outline_bytes(tables, cm[ord(c)]))


def book_korean() -> dict[str, str]:
    """Every Korean character the book shows, with where it first occurs."""
    found = {}
    for q in quotes.QUOTES.values():
        for field in ("original", "translation", "where"):
            for ch in getattr(q, field):
                if is_korean(ch):
                    found.setdefault(ch, f"quote {q.key} ({field})")
    for page in sorted((ROOT / "book").glob("*.md")):
        for ch in page.read_text(encoding="utf-8"):
            if is_korean(ch):
                found.setdefault(ch, f"book/{page.name}")
    return found


# ---- a WOFF made by hand: the reader's oracle ---------------------------------------------

def _table(tag: bytes, body: bytes, compress: bool):
    packed = zlib.compress(body) if compress else body
    return tag, body, packed if len(packed) < len(body) else body


def hand_woff() -> bytes:
    """Three glyphs: 가 (U+AC00) -> 1 by idDelta, 각 (U+AC01) -> 2 through the glyph id array
    (format 4), 𠀀 (U+20000) -> 1 (format 12); glyph 1 has 8 bytes of outline, glyph 2 none
    (각 maps to an empty glyph, so it is not drawn); 갂 (U+AC02) is in no subtable."""
    # format 4: segments [AC00, AC00] delta 1-0xAC00, [AC01, AC01] through glyphIdArray, [FFFF]
    seg = 3
    ends, starts = [0xAC00, 0xAC01, 0xFFFF], [0xAC00, 0xAC01, 0xFFFF]
    deltas = [(1 - 0xAC00) & 0xFFFF, 0, 1]
    # segment 1's idRangeOffset points from its own entry to glyphIdArray[0]: 2 entries on
    ranges = [0, 4, 0]
    glyph_ids = [2]
    body4 = struct.pack(f">HHHHHHH{seg}HH{seg}H{seg}H{seg}H{len(glyph_ids)}H", 4, 0, 0, 2 * seg,
                        4, 1, 2, *ends, 0, *starts, *deltas, *ranges, *glyph_ids)
    body4 = body4[:2] + struct.pack(">H", len(body4)) + body4[4:]
    body12 = struct.pack(">HHIII" + "III", 12, 0, 28, 0, 1, 0x20000, 0x20000, 1)
    header = struct.pack(">HH", 0, 2)
    rec4 = struct.pack(">HHI", 3, 1, 4 + 16)
    rec12 = struct.pack(">HHI", 3, 10, 4 + 16 + len(body4))
    cmap_t = header + rec4 + rec12 + body4 + body12
    head = bytearray(54)
    head[50:52] = struct.pack(">h", 0)                  # short loca
    maxp = struct.pack(">IH", 0x5000, 3)
    loca = struct.pack(">4H", 0, 0, 4, 4)               # glyph 1: bytes 0-8, glyph 2: empty
    glyf = bytes(8)
    tables = [_table(b"cmap", cmap_t, True), _table(b"glyf", glyf, False),
              _table(b"head", bytes(head), True), _table(b"loca", loca, False),
              _table(b"maxp", maxp, False)]
    offset = 44 + 20 * len(tables)
    directory, blobs = b"", b""
    for tag, body, stored in tables:
        directory += struct.pack(">4sIIII", tag, offset + len(blobs), len(stored), len(body), 0)
        blobs += stored + bytes(-len(stored) % 4)
    total = offset + len(blobs)
    return struct.pack(">4sIIHHIHHIIIII", b"wOFF", 0x00010000, total, len(tables), 0, 0,
                       1, 0, 0, 0, 0, 0, 0) + directory + blobs


def test_woff_reader_on_a_font_made_by_hand():
    data = hand_woff()
    tables = woff_tables(data)
    assert cmap(tables) == {0xAC00: 1, 0xAC01: 2, 0x20000: 1}
    assert outline_bytes(tables, 1) == 8 and outline_bytes(tables, 2) == 0
    assert missing(data, "가각갂𠀀") == ["각", "갂"]


# ---- the committed font -----------------------------------------------------------------

def test_font_draws_every_korean_character_of_the_book():
    found = book_korean()
    assert len(found) > 300                       # the register quotes hundreds of syllables
    lacking = missing(FONT.read_bytes(), found)
    assert not lacking, (
        "the shipped Korean font has no glyph for "
        + ", ".join(f"{c} (U+{ord(c):04X}, {found[c]})" for c in lacking)
        + ": run book/_ext/subset_korean_font.py (its docstring says how)")


def test_font_lacks_what_the_book_does_not_show():
    """The check fails on a character the subset leaves out: 똠 and 뷁 are in no quote and no
    page, and the subset keeps no Hanja."""
    data = FONT.read_bytes()
    assert not {"똠", "뷁", "漢"} & set(book_korean())
    assert missing(data, "가똠뷁漢") == sorted("똠뷁漢")


def test_font_is_a_small_zlib_woff():
    data = FONT.read_bytes()
    assert data[:4] == b"wOFF"
    n = struct.unpack(">H", data[12:14])[0]
    stored = {tag: (comp, orig) for tag, _, comp, orig, _ in
              (struct.unpack(">4sIIII", data[44 + 20 * i:64 + 20 * i]) for i in range(n))}
    assert stored[b"glyf"][0] < stored[b"glyf"][1]     # the outlines are stored deflated
    assert len(data) < 60_000, f"{len(data)} bytes: the subset should hold only the book's glyphs"
    n_glyphs = struct.unpack(">H", woff_tables(data)["maxp"][4:6])[0]
    assert n_glyphs < len(book_korean()) + 20


def test_stylesheet_declares_the_face_relative_to_itself():
    css = CSS.read_text(encoding="utf-8")
    face = re.search(r"@font-face\s*\{(.*?)\}", css, re.S).group(1)
    assert f'font-family: "{FONT_FACE}"' in face
    url = re.search(r'url\("([^"]+)"\)\s*format\("woff"\)', face).group(1)
    assert not re.match(r"^(/|[a-z]+:)", url), "an absolute URL breaks file:// or a sub-path"
    assert (CSS.parent / url).resolve() == FONT.resolve()
    spans = [(int(a, 16), int(b, 16)) for a, b in
             re.findall(r"U\+([0-9A-F]+)-([0-9A-F]+)", re.search(r"unicode-range:([^;]+);",
                                                                face).group(1))]
    assert spans == list(KOREAN_BLOCKS)            # nothing else: Latin keeps the theme's font
    assert css.count("url(") == 1                 # nothing else is fetched
    licence = (FONT.parent / "OFL.txt").read_text(encoding="utf-8")
    assert "SIL OPEN FONT LICENSE Version 1.1" in licence and "Noto Sans KR" in licence


def test_korean_blocks_are_the_regeneration_scripts():
    """The script that makes the font keeps the characters of the same blocks."""
    src = (ROOT / "book" / "_ext" / "subset_korean_font.py").read_text(encoding="utf-8")
    block = re.search(r"^KOREAN = (\(\(.*?\)\))$", src, re.S | re.M).group(1)
    assert [(int(a, 16), int(b, 16)) for a, b in re.findall(r"0x([0-9A-F]+), 0x([0-9A-F]+)",
                                                            block)] == list(KOREAN_BLOCKS)


# ---- in Chromium, on a one-page book --------------------------------------------------------

#: a quote in Korean and Korean in the page's own text (겹침: occlusion, as Cho and Kang write)
PAGE = """# Korean

Occlusion, which Cho and Kang call 겹침, is where the tracker fails
{quote}`cho2005.occlusion_single`.
"""


@pytest.fixture(scope="module")
def one_page_book(tmp_path_factory):
    """The page built with the book's theme, its ``_static`` and the quote extension, the
    stylesheets of ``_static`` added to the page as Jupyter Book adds them."""
    pytest.importorskip("myst_parser")
    pytest.importorskip("sphinx_book_theme")
    from sphinx.application import Sphinx

    tmp = tmp_path_factory.mktemp("korean")
    src, out = tmp / "src", tmp / "out"
    src.mkdir()
    (src / "conf.py").write_text("", encoding="utf-8")
    (src / "index.md").write_text(PAGE, encoding="utf-8")
    static = ROOT / "_static"
    app = Sphinx(str(src), str(src), str(out), str(tmp / ".doctrees"), "html",
                 confoverrides={"extensions": ["myst_parser", "sphinx_quotes"],
                                "html_theme": "sphinx_book_theme",
                                "html_static_path": [str(static)],
                                "html_css_files": sorted(p.relative_to(static).as_posix()
                                                         for p in static.rglob("*.css"))},
                 status=None, warning=None, freshenv=True)
    app.build(force_all=True)
    return out


@pytest.mark.browser
@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium (apt-get install chromium)")
@pytest.mark.parametrize("scheme", ["file", "http"])
def test_korean_is_drawn_with_the_shipped_face(browser, one_page_book, scheme):
    assert quotes.quote("cho2005.occlusion_single").language == "ko"
    httpd, base = serve(one_page_book)
    try:
        root = one_page_book.as_uri() if scheme == "file" else base
        seen = font_check(browser, root, "index.html", "cho2005.occlusion_single",
                          prose="article p")
    finally:
        httpd.shutdown()
    assert not seen["problems"], seen

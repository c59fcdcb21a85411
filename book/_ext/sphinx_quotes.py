"""Sphinx extension: the evidence beside a sentence that speaks for a paper.

The role ``{quote}`lee2012.window40``` (MyST; ``:quote:`lee2012.window40``` in reST) renders
a small superscript marker after the sentence. Its ``title`` (a hover tooltip) holds the
translation; hovering, tapping or tabbing to it opens a popover with the passage word for word
(Korean, or the English abstract), the English translation, where it comes from
and whether it is printed or a reading. The page ends with the list of its evidence, which
also serves print and readers without hover. Plain CSS, no script, no network: it works from
``file://`` and over http, and the popover fits a 390 px screen.

An unknown key stops the build with a message naming the key, its page and line.

``quotes_check_attributions`` (``"off"``, ``"warn"`` or ``"error"``, default ``"off"``) also
reads every Markdown page for sentences that speak for a paper without a quote in their
paragraph (:mod:`trackbook.quotes.attributions`). Enabled in ``_config.yml``
(``sphinx.extra_extensions``).
"""

from __future__ import annotations

import html
import re
from pathlib import Path

from docutils import nodes
from sphinx.errors import ExtensionError
from sphinx.util import logging

from trackbook import quotes
from trackbook.quotes import attributions

logger = logging.getLogger(__name__)

CSS_NAME = "trackbook-quotes.css"

#: How each paper is named to the reader.
AUTHORS = {"lee2012": "Lee et al. (2012)", "kim2016": "Kim et al. (2016)",
           "lee2015": "Lee (2015)", "cho2005": "Cho and Kang (2005)"}

CSS = """\
/* trackbook: evidence markers ({quote} role) */
.tb-quote { position: relative; display: inline; }
.tb-quote-mark { font-size: 0.7em; line-height: 0; vertical-align: super; cursor: help;
  color: #0072b2; padding: 0 0.1em; border-bottom: 1px dotted currentColor; }
.tb-quote:focus { outline: 2px solid #0072b2; outline-offset: 1px; }
/* fixed to the viewport's lower corner: never wider than the screen, never pushes the page
   sideways wherever the marker sits on its line */
.tb-quote-pop { display: none; position: fixed; right: 1rem; bottom: 1rem; z-index: 1050;
  width: 28rem; max-width: calc(100vw - 2rem); max-height: 60vh; overflow: auto;
  padding: 0.6em 0.8em; background: var(--pst-color-surface, #fff);
  color: var(--pst-color-text-base, #222); border: 1px solid #999; border-radius: 4px;
  box-shadow: 0 2px 8px rgba(0, 0, 0, 0.25); font-size: 0.85rem; line-height: 1.4;
  font-weight: normal; font-style: normal; text-align: left; white-space: normal; }
.tb-quote:hover .tb-quote-pop, .tb-quote:focus .tb-quote-pop,
.tb-quote:focus-within .tb-quote-pop { display: block; }
.tb-quote-pop > span, .tb-quote-list li > span { display: block; overflow-wrap: anywhere; }
.tb-quote-src { font-weight: 600; margin-bottom: 0.3em; }
.tb-quote-orig { margin-bottom: 0.3em; }
.tb-quote-tr { font-style: italic; }
.tb-quote-kind { font-size: 0.8em; opacity: 0.8; }
.tb-quote-list { font-size: 0.9rem; margin-top: 2em; }
.tb-quote-list li { margin-bottom: 0.6em; }
@media (max-width: 600px) {
  .tb-quote-pop { left: 0.5rem; right: 0.5rem; bottom: 0.5rem; width: auto; max-width: none;
    max-height: 50vh; }
}
@media print { .tb-quote-pop { display: none !important; } }
"""


class quote_ref(nodes.Inline, nodes.Element):
    """A reference to one quote of the register (attribute ``key``)."""


class quote_list(nodes.General, nodes.Element):
    """The page's list of evidence, appended after its last section."""


def label(q: quotes.Quote) -> str:
    """``Lee et al. (2012), §IV, ...`` — who and where."""
    return f"{AUTHORS[q.paper]}, {q.where}"


def _kind(q: quotes.Quote) -> str:
    return ("printed" if q.kind == "printed"
            else "a reading: the passage is ambiguous; the book reads it this way")


def quote_role(name, rawtext, text, lineno, inliner, options=None, content=None):
    """``{quote}`key```: a marker showing the quote registered under ``key``."""
    key = text.strip()
    try:
        quotes.quote(key)
    except ValueError as e:
        source = inliner.document.get("source", "?")
        raise ExtensionError(f"{source}:{lineno}: {e}") from None
    node = quote_ref(rawtext, key=key)
    return [node], []


def _balanced(tex: str) -> bool:
    depth = 0
    for ch in re.sub(r"\\[{}]", "", tex):
        depth += {"{": 1, "}": -1}.get(ch, 0)
        if depth < 0:
            return False
    return depth == 0


#: TeX left outside ``$`` in a passage as the seeds print it (``\dot{x}``, ``H_x``,
#: ``\mathbf{w}_{t-1}``, ``S'_{t-1}``): a command with its braced arguments or a letter, then
#: primes and sub- or superscripts; a command needs none of those, a letter at least one.
_BARE_TEX = re.compile(
    r"(?<![\w\\])(?:\\[A-Za-z]+(?:\{[^{}$]*\})*|[A-Za-z])'*"
    r"(?:[_^](?:\{[^{}$]*\}|[A-Za-z0-9]))*")


def _wrap_bare(piece: str) -> str:
    """Each run of TeX in ``piece`` (text outside ``$``) inside ``\\( \\)``."""
    def wrap(m):
        tex = m.group(0)
        if tex.startswith("\\") or re.search(r"[_^]", tex):
            return f"\\({tex}\\)"
        return tex
    return _BARE_TEX.sub(wrap, piece)


def _typeset(text: str):
    """The passage ready for MathJax (``$ $``/``$$ $$``/``\\( \\)``, typeset on the page), or
    None.

    A passage cut inside a display equation lacks one ``$$``: it is added on the cut side. TeX
    the seeds print outside any ``$`` (``\\dot{x}``, ``H_x``) is put inside ``\\( \\)``, so
    the reader sees it typeset, never as source. A passage whose TeX MathJax cannot typeset as
    it stands (a fragment with unbalanced braces, a lone ``$``) gives None; the register holds
    none (``tests/test_quote_typeset.py``).
    """
    if text.count("$$") % 2:
        text = text + "$$" if text.lstrip().startswith("$$") else "$$" + text
    pieces = re.split(r"(\$\$.*?\$\$|\$[^$]*\$)", text, flags=re.S)
    if not all(_balanced(m) for m in pieces[1::2]) or any("$" in t for t in pieces[0::2]):
        return None
    pieces[0::2] = [_wrap_bare(t) for t in pieces[0::2]]
    if any(re.search(r"\\[A-Za-z]", re.sub(r"\\\(.*?\\\)", "", t)) or not _balanced(t)
           for t in pieces[0::2]):
        return None
    return "".join(pieces)


def _body(q: quotes.Quote, esc=html.escape) -> str:
    lang = "ko" if q.language == "ko" else "en"
    tex = _typeset(q.original)
    orig = (f'<span class="tb-quote-orig mathjax_process" lang="{lang}">{esc(tex)}</span>'
            if tex is not None else
            f'<span class="tb-quote-orig" lang="{lang}"><code>{esc(q.original)}</code></span>')
    return (f'<span class="tb-quote-src">{esc(label(q))}</span>{orig}'
            f'<span class="tb-quote-tr mathjax_process" lang="en">{esc(q.translation)}</span>'
            f'<span class="tb-quote-kind">{esc(_kind(q))}</span>')


def visit_quote_ref_html(self, node):
    q = quotes.quote(node["key"])
    n = node["number"]
    title = f"{label(q)}: {q.translation}"
    self.body.append(
        f'<span class="tb-quote mathjax_ignore tex2jax_ignore" tabindex="0" '
        f'data-quote="{html.escape(q.key)}" aria-label="evidence {n}: '
        f'{html.escape(label(q))}"><sup class="tb-quote-mark" '
        f'title="{html.escape(title)}">q{n}</sup>'
        f'<span class="tb-quote-pop" role="note">{_body(q)}</span></span>')
    raise nodes.SkipNode


def visit_quote_list_html(self, node):
    items = []
    for n, key in enumerate(node["keys"], 1):
        items.append(f'<li id="tb-quote-{n}" value="{n}">{_body(quotes.quote(key))}</li>')
    self.body.append(
        '<div class="tb-quote-list mathjax_ignore tex2jax_ignore">'
        '<p class="rubric">Evidence on this page</p>'
        f'<ol>{"".join(items)}</ol></div>')
    raise nodes.SkipNode


def _resolve(app, doctree, docname):
    """Number the page's markers; add the evidence list (HTML) or plain text (others)."""
    refs = list(doctree.findall(quote_ref))
    if not refs:
        return
    html_builder = app.builder.format == "html"
    for n, node in enumerate(refs, 1):
        node["number"] = n
        if not html_builder:
            q = quotes.quote(node["key"])
            node.replace_self(nodes.Text(f" [{label(q)}: {q.translation}]"))
    if html_builder:
        doctree.append(quote_list(keys=[node["key"] for node in refs]))


def _has_tex(q: quotes.Quote) -> bool:
    tex = _typeset(q.original)
    return tex is not None and ("$" in tex or "\\(" in tex)


def _load_mathjax(app, doctree):
    """A page whose popovers hold TeX loads MathJax even when its own text has no maths.

    Sphinx adds MathJax only to pages with equations (its math domain's ``has_equations``);
    the popovers' passages are raw HTML, not maths nodes, so their page is marked here. Only
    a MathJax served with the book (``sphinx_offline_mathjax``) is added this way:
    a page never asks a CDN for its popovers.
    """
    path = str(getattr(app.config, "mathjax_path", "") or "")
    if not path or re.match(r"^(https?:)?//", path):
        return
    if any(_has_tex(quotes.quote(n["key"])) for n in doctree.findall(quote_ref)):
        try:
            domain = app.env.get_domain("math")
        except Exception:  # noqa: BLE001  no math domain: nothing typesets anyway
            return
        domain.data["has_equations"][app.env.docname] = True


def _check_source(app, docname, source):
    """``quotes_check_attributions``: flag unquoted attribution sentences of a page."""
    mode = app.config.quotes_check_attributions
    if mode == "off":
        return
    path = app.env.doc2path(docname)
    if Path(path).suffix != ".md":
        return
    found = attributions.unquoted(source[0])
    for line, sentence in found:
        msg = f"attribution without a quote: {sentence}"
        if mode == "error":
            raise ExtensionError(f"{path}:{line}: {msg}")
        logger.warning(msg, location=(docname, line), type="trackbook", subtype="quotes")


def _check_mode(app, config):
    if config.quotes_check_attributions not in ("off", "warn", "error"):
        raise ExtensionError(f"quotes_check_attributions = "
                             f"{config.quotes_check_attributions!r}: use 'off', 'warn' or "
                             f"'error'")


def _write_css(app, exception):
    if exception is None and app.builder.format == "html":
        static = Path(app.outdir) / "_static"
        static.mkdir(parents=True, exist_ok=True)
        (static / CSS_NAME).write_text(CSS, encoding="utf-8")


def setup(app):
    app.add_config_value("quotes_check_attributions", "off", "env")
    app.add_node(quote_ref, html=(visit_quote_ref_html, None))
    app.add_node(quote_list, html=(visit_quote_list_html, None))
    app.add_role("quote", quote_role)
    app.add_css_file(CSS_NAME)
    app.connect("config-inited", _check_mode)
    app.connect("source-read", _check_source)
    app.connect("doctree-read", _load_mathjax)
    app.connect("doctree-resolved", _resolve)
    app.connect("build-finished", _write_css)
    return {"parallel_read_safe": True, "parallel_write_safe": True}

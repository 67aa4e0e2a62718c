"""MkDocs hook: the docstrings' Sphinx cross-reference roles shown as plain code on the API pages.

The docstrings name objects as Sphinx does (``:func:`~throwmap.throws.throw.throw```, ``:class:`Part```); the Python
handler of mkdocstrings renders such a role as the literal ``:func:`` followed by the code. This hook drops the role
and, as Sphinx does for a leading ``~``, shows only the last component of the dotted name.
"""

from __future__ import annotations

import re

ROLE = re.compile(r":(?:func|class|mod|data|attr|meth|exc|obj|const|term|ref):<code>~?([^<]*)</code>")


def _show(match: re.Match) -> str:
    name = match.group(1)
    tilde = match.group(0).split("<code>", 1)[1].startswith("~")
    return f"<code>{name.rsplit('.', 1)[-1] if tilde else name.lstrip('.')}</code>"


def on_page_content(html: str, **kwargs) -> str:
    return ROLE.sub(_show, html)

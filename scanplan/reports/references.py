"""References of the reports: the bundled bibliography and a per-document citation list.

The norm tables' ``source`` cells and the message catalogue name a work by a short form
("Miheeva & Ilushenko 2015, Table 3", "GKINP (GNTA)-02-036-02; Miheeva & Ilushenko 2015,
eq. 1", "Михеева, Илюшенко, 2015, ф. (16)"). A document numbers the works in the order it
first cites them: each short form becomes ``[n]`` and its locator is written in the
document's language ("[2], Table 3", "[2], табл. 3"); the list of references closes the
document. A cell that names none of the known works — already a full citation, such as a
user's norm set — is shown as is.

The bibliography is data: ``norms/references.toml`` (each work in English and Russian,
the short forms it is cited by, and the old names of norm files written by earlier
versions: recognised too, and never printed).
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache

from ..norms import bundled_norms_dir

__all__ = ["Bibliography", "Reference", "author_cite", "references"]


@dataclass(frozen=True)
class Reference:
    """One work: its id, the short forms that cite it, its entry in both languages, and
    the old names norm files of earlier versions cite it by (read, never printed)."""

    id: str
    aliases: tuple[str, ...]
    en: str
    ru: str
    old_aliases: tuple[str, ...] = ()

    def text(self, locale: str) -> str:
        """The bibliographic entry in ``locale`` (the Russian original in Russian)."""
        return self.ru if locale == "ru" else self.en


@cache
def references() -> tuple[Reference, ...]:
    """The bundled bibliography (``norms/references.toml``)."""
    data = tomllib.loads((bundled_norms_dir() / "references.toml").read_text("utf-8"))
    return tuple(Reference(id=r["id"], aliases=tuple(r["aliases"]), en=r["en"], ru=r["ru"],
                           old_aliases=tuple(r.get("old_aliases", ())))
                 for r in data["reference"])


@cache
def _alias_pattern() -> tuple[re.Pattern[str], dict[str, Reference]]:
    by_alias = {a.casefold(): ref for ref in references()
                for a in (*ref.aliases, *ref.old_aliases)}
    alts = sorted(by_alias, key=len, reverse=True)
    pattern = re.compile("|".join(re.escape(a) for a in alts), re.IGNORECASE)
    return pattern, by_alias


# Locators as the norm tables write them → (English, Russian) wording, applied in order;
# None: the locator is left as written in that language.
_LOCATORS: tuple[tuple[str, str | None, str], ...] = (
    (r"\bAppendix B, Table B\.1", None, "прил. Б, табл. Б.1"),
    (r"\bTable B\.1", None, "табл. Б.1"),
    (r"\bfootnote: towns with dense multi-storey buildings", None,
     "сноска: городские населённые пункты с многоэтажной и плотной застройкой"),
    (r"§(\d+)\.(\d+)\.(\d+)", None, r"п. \1.\2.\3"),
    (r"\bconclusions after Table (\d+)", r"conclusions after Table \1",
     r"выводы после табл. \1"),
    (r"\bTable (\d+) discussion", r"discussion of Table \1", r"пояснения к табл. \1"),
    (r"\b(?:its )?ref\. \[(\d+)\]", r"its reference \1", r"его источник № \1"),
    (r"\beqs\. \(?(\d+)\)?\s*[-–]\s*\(?(\d+)\)?", r"eqs. (\1)–(\2)", r"ф. (\1)–(\2)"),
    (r"\beq\. \(?(\d+)\)?", r"eq. (\1)", r"ф. (\1)"),
    (r"\bTables? (\d+)", None, r"табл. \1"),
    (r"\bconclusion (\d+)", r"conclusion \1", r"вывод \1"),
    (r"\bworked example\b", None, "пример расчёта"),
    (r"\bas printed\b", None, "в печатной редакции"),
    (r"\bafter\b", None, "после"),
    (r"\band\b", None, "и"),
    (r"\bplus\b", None, "и"),
    (r"\bwith\b", None, "с"),
    (r"(?<![\d.])(\d+)\.(\d+)(?![.\d])", None, r"\1,\2"),
)


def _locator(text: str, locale: str) -> str:
    for pattern, en, ru in _LOCATORS:
        repl = ru if locale == "ru" else en
        if repl is not None:
            text = re.sub(pattern, repl, text)
    return text


def _short_name(ref: Reference, locale: str) -> str:
    """The work's short form a reader knows (authors and year), never an old name: the
    first Cyrillic alias in Russian, else the first Latin one."""
    names = list(ref.aliases)
    cyrillic = [a for a in names if re.search("[А-Яа-яЁё]", a)]
    latin = [a for a in names if a not in cyrillic]
    pick = (cyrillic or latin) if locale == "ru" else (latin or cyrillic)
    return pick[0] if pick else ref.id


def author_cite(text: str, locale: str) -> str:
    """``text`` with every short form of a known work written as its authors and year
    (``Miheeva & Ilushenko 2015, Table 3``; ``Михеева, Илюшенко, 2015, табл. 3``) — for
    output without a reference list (the terminal), where ``[n]`` would point nowhere.

    Parameters
    ----------
    text : str
        A source cell or a sentence citing a work.
    locale : {"en", "ru"}

    Returns
    -------
    str
    """
    return _replace_citations(text, locale, lambda ref: _short_name(ref, locale))


def _replace_citations(text: str, locale: str, name: Callable[[Reference], str]) -> str:
    """``text`` with every short form of a known work replaced by ``name(work)`` and the
    locators after it (``Table 3``, ``eq. (16)``) written in ``locale``; text before the
    first short form kept, a text naming no known work returned unchanged."""
    pattern, by_alias = _alias_pattern()
    matches = list(pattern.finditer(text))
    if not matches:
        return text
    out = [text[:matches[0].start()]]
    for i, m in enumerate(matches):
        ref = by_alias[m.group().casefold()]
        end = matches[i + 1].start() if i + 1 < len(matches) else len(text)
        rest = _locator(text[m.end():end], locale)
        if rest and not rest.startswith((",", ";", ")", " —", ".")) and rest.strip():
            rest = ", " + rest.lstrip()
        out.append(name(ref) + rest)
    return "".join(out)


@dataclass
class Bibliography:
    """The references one document cites, numbered in order of first citation.

    Parameters
    ----------
    locale : {"en", "ru"}
        The document's language.
    cited : list of Reference, optional
        The numbering: the works in order of first citation. Documents of one set (the
        PDF and the workbook of a run) share this list, so a work has one number in all
        of them; each lists only the works it cites itself.
    """

    locale: str
    cited: list[Reference] = field(default_factory=list)
    used: set[str] = field(default_factory=set)

    def number(self, ref: Reference) -> int:
        """The reference's number in this document (cited now if it was not yet)."""
        if ref not in self.cited:
            self.cited.append(ref)
        self.used.add(ref.id)
        return self.cited.index(ref) + 1

    def cite(self, text: str) -> str:
        """``text`` with every short form of a known work replaced by ``[n]`` and the
        locators after it written in the document's language.

        Text before the first short form (a formula, a sentence) is kept as it is; a text
        that names no known work is returned unchanged.

        Parameters
        ----------
        text : str
            A source cell or a sentence citing a work.

        Returns
        -------
        str
        """
        return _replace_citations(text, self.locale, lambda ref: f"[{self.number(ref)}]")

    def entries(self) -> list[tuple[int, str]]:
        """(number, entry) of every work cited so far, in the document's language."""
        return [(i, ref.text(self.locale)) for i, ref in enumerate(self.cited, 1)
                if ref.id in self.used]

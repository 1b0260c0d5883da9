"""Compare the PDFs of two folders (or two PDF files) as pictures, page by page.

``tools/compare_outputs.py`` reads a PDF as its text; a change that must leave every page
looking the same (a stylesheet made cheaper to lay out, a table's borders drawn another
way) is proven with this script instead::

    python tools/compare_pages.py BEFORE AFTER [--dpi 100] [--diffs DIR]

Every ``*.pdf`` under the folder ``BEFORE`` (by its path relative to the folder; an output
set's own folder ``.scanplan-sets/`` is read through the output folder's links, as
``compare_outputs.py`` does) is compared with the file of the same path under ``AFTER``.
Each PDF is rasterised with poppler's ``pdftoppm -png -r DPI`` (a file whose bytes are
those of one already rasterised is not rasterised again) and each page compared pixel by
pixel (Pillow's ``ImageChops.difference``): the count of pixels that differ in any colour
channel and the largest difference of a channel (0–255). A PDF missing on either side, or
with another page count, or a page of another size, is a difference too. With ``--diffs``,
each differing page is written there as ``NAME-pPAGE-before.png``, ``-after.png`` and
``-diff.png`` (the difference, stretched to be seen) to look at.

Prints one line per differing page and a summary; exits 0 when every page of every PDF is
the same picture, 1 otherwise.
"""

from __future__ import annotations

import argparse
import hashlib
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from compare_outputs import reader_files
from PIL import Image, ImageChops


@dataclass(frozen=True)
class PageDiff:
    """One page of a PDF as two pictures.

    Attributes
    ----------
    page : int
        The page number, from 1.
    pixels : int
        Pixels that differ in any channel (−1: the pages' sizes differ).
    max_diff : int
        The largest difference of one channel of one pixel, 0–255.
    """

    page: int
    pixels: int
    max_diff: int


def rasterise(pdf: Path, into: Path, dpi: int = 100) -> list[Path]:
    """The pages of ``pdf`` as PNG files (``pdftoppm -png -r DPI``) in the folder ``into``.

    Parameters
    ----------
    pdf : Path
        The PDF file.
    into : Path
        A folder for this PDF's pages (made; its PNG files are the pages).
    dpi : int
        The resolution [dots per inch].

    Returns
    -------
    list of Path
        The pages, in order.
    """
    into.mkdir(parents=True, exist_ok=True)
    subprocess.run(["pdftoppm", "-png", "-r", str(dpi), str(pdf), str(into / "p")],
                   check=True, capture_output=True)
    # pdftoppm pads the page number to the width of the last one: sort by number
    return sorted(into.glob("p-*.png"), key=lambda p: int(p.stem.rsplit("-", 1)[1]))


def compare_images(before: Path, after: Path, page: int) -> PageDiff:
    """The difference of two page pictures (:class:`PageDiff`)."""
    with Image.open(before) as a, Image.open(after) as b:
        if a.size != b.size:
            return PageDiff(page, -1, 255)
        diff = ImageChops.difference(a.convert("RGB"), b.convert("RGB"))
        if diff.getbbox() is None:
            return PageDiff(page, 0, 0)
        max_diff = max(hi for _, hi in diff.getextrema())  # each band's largest
        mask = None  # a pixel differs when any of its channels does
        for band in diff.split():
            band = band.point(lambda v: 255 if v else 0)
            mask = band if mask is None else ImageChops.lighter(mask, band)
        pixels = mask.histogram()[255]
        return PageDiff(page, pixels, max_diff)


class _Pages:
    """The pages of PDFs rasterised once per distinct file content (by SHA-256)."""

    def __init__(self, work: Path, dpi: int) -> None:
        self.work, self.dpi = work, dpi
        self.done: dict[str, list[Path]] = {}

    def key(self, pdf: Path) -> str:
        return hashlib.sha256(pdf.read_bytes()).hexdigest()

    def pages(self, key: str, pdf: Path) -> list[Path]:
        if key not in self.done:
            self.done[key] = rasterise(pdf, self.work / key, self.dpi)
        return self.done[key]


def compare_pdfs(before: Path, after: Path, pages: _Pages) -> tuple[int, list[PageDiff], str]:
    """Compare two PDF files as pictures.

    Returns
    -------
    tuple
        (pages compared, the differing pages, a note: "" or why the files cannot be
        compared page by page).
    """
    if not after.is_file():
        return 0, [], "missing after"
    ka, kb = pages.key(before), pages.key(after)
    a = pages.pages(ka, before)
    if ka == kb:
        return len(a), [], ""
    b = pages.pages(kb, after)
    # the common pages; another page count is reported in the note
    diffs = [d for k, (pa, pb) in enumerate(zip(a, b, strict=False), start=1)
             if (d := compare_images(pa, pb, k)).pixels]
    note = "" if len(a) == len(b) else f"{len(a)} pages before, {len(b)} after"
    return min(len(a), len(b)), diffs, note


def _pdfs(root: Path) -> list[Path]:
    """The PDFs under ``root`` by the names a reader sees: an output folder's files through
    their links, not the output set's own folder (``.scanplan-sets/HASH/``, whose name
    differs from run to run): ``compare_outputs.reader_files``."""
    if root.is_file():
        return [Path(root.name)]
    return sorted(Path(f) for f in reader_files(root) if f.endswith(".pdf"))


def _save_diff(name: str, page: int, a: Path, b: Path, into: Path) -> None:
    into.mkdir(parents=True, exist_ok=True)
    stem = f"{name.replace('/', '_').removesuffix('.pdf')}-p{page}"
    shutil.copy2(a, into / f"{stem}-before.png")
    shutil.copy2(b, into / f"{stem}-after.png")
    with Image.open(a) as ia, Image.open(b) as ib:
        diff = ImageChops.difference(ia.convert("RGB"), ib.convert("RGB"))
        ImageChops.invert(diff.point(lambda v: min(255, v * 8))).save(into / f"{stem}-diff.png")


def main(argv: list[str] | None = None) -> int:
    """The command line (the module's docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n", 1)[0])
    parser.add_argument("before", type=Path, help="a folder of PDFs, or one PDF")
    parser.add_argument("after", type=Path, help="the same, after the change")
    parser.add_argument("--dpi", type=int, default=100, help="resolution (default 100)")
    parser.add_argument("--diffs", type=Path, help="write each differing page's pictures here")
    parser.add_argument("--jobs", type=int, default=2, help="PDFs rasterised at once")
    args = parser.parse_args(argv)
    if shutil.which("pdftoppm") is None:
        parser.error("pdftoppm (poppler-utils) is not installed")
    names = _pdfs(args.before)
    if not names:
        parser.error(f"no PDF under {args.before}")

    def path(root: Path, name: Path) -> Path:
        return root if root.is_file() else root / name

    extra = [] if args.after.is_file() else sorted(set(_pdfs(args.after)) - set(names))
    with tempfile.TemporaryDirectory(prefix="compare-pages-") as tmp:
        pages = _Pages(Path(tmp), args.dpi)
        # rasterise every distinct file first, in parallel; then compare in order
        todo = {}
        for name in names:
            for root in (args.before, args.after):
                if path(root, name).is_file():
                    todo.setdefault(pages.key(path(root, name)), path(root, name))
        with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            list(pool.map(lambda kv: pages.pages(*kv), todo.items()))
        compared = differing = bad_files = 0
        for name in names:
            a, b = path(args.before, name), path(args.after, name)
            n, diffs, note = compare_pdfs(a, b, pages)
            compared += n
            differing += len(diffs)
            if note:
                bad_files += 1
                print(f"{name}: {note}")
            for d in diffs:
                size = "another page size" if d.pixels < 0 else f"{d.pixels} pixels differ"
                print(f"{name} page {d.page}: {size}, max difference {d.max_diff}")
                if args.diffs is not None:
                    _save_diff(str(name), d.page, pages.done[pages.key(a)][d.page - 1],
                               pages.done[pages.key(b)][d.page - 1], args.diffs)
        for name in extra:
            bad_files += 1
            print(f"{name}: only after")
    print(f"{len(names)} PDFs, {compared} pages compared at {args.dpi} dpi: "
          f"{differing} pages differ, {bad_files} files not comparable page by page")
    return 1 if differing or bad_files else 0


if __name__ == "__main__":
    sys.exit(main())

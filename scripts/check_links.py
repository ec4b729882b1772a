#!/usr/bin/env python3
"""Checks the internal links of a built mdBook: every relative href and src
of every page must name a file of the book, and every #fragment an id (or
name) on the page it points to. External links (with a scheme such as
https:) are not followed: the machines that run the tests reach only the
package registries.

Usage: scripts/check_links.py [BOOK_DIR]   (default docs/book)
Exit 0 when every link resolves, 1 otherwise (each broken link is listed
with the page it is on), 2 when the book is missing.
"""

import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

# Pages mdBook generates that repeat or stand in for the chapters.
SKIP_PAGES = {"print.html", "toc.html", "404.html"}


class Page(HTMLParser):
    """The ids of a page and the links on it."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.ids = set()
        self.links = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        for key in ("id", "name") if tag == "a" else ("id",):
            if a.get(key):
                self.ids.add(a[key])
        for key in ("href", "src"):
            if a.get(key) and tag in ("a", "img", "link", "script", "source"):
                self.links.append((tag, a[key]))


def parse(path, cache):
    if path not in cache:
        page = Page()
        page.feed(path.read_text(encoding="utf-8"))
        cache[path] = page
    return cache[path]


def main():
    book = Path(sys.argv[1] if len(sys.argv) > 1 else "docs/book").resolve()
    if not (book / "index.html").is_file():
        print(f"check_links: no built book at {book} (run mdbook build first)", file=sys.stderr)
        return 2
    cache = {}
    broken = []
    pages = sorted(p for p in book.rglob("*.html") if p.name not in SKIP_PAGES)
    checked = 0
    for page_path in pages:
        page = parse(page_path, cache)
        for tag, link in page.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith("javascript:"):
                continue  # external: not followed
            checked += 1
            where = page_path.relative_to(book)
            if parts.path:
                target = (page_path.parent / unquote(parts.path)).resolve()
                if target.is_dir():
                    target = target / "index.html"
                if not target.is_file():
                    broken.append(f"{where}: {tag} {link}: no such file in the book")
                    continue
            else:
                target = page_path
            fragment = unquote(parts.fragment)
            if fragment and target.suffix == ".html":
                if fragment not in parse(target, cache).ids:
                    broken.append(f"{where}: {link}: no anchor #{fragment} on {target.relative_to(book)}")
    for b in broken:
        print(f"broken link: {b}", file=sys.stderr)
    print(f"check_links: {len(pages)} pages, {checked} internal links, {len(broken)} broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())

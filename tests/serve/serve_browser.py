#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The `morphex serve` page in a real browser: headless Chromium (Debian's chromium, installed by
scripts/setup) loads the page from a server on an index of generated meshes, runs a query from the
address (#query=tee-1&...), and the page's DOM is checked: the neighbours' names in the order of
`morphex query`, the 3D view drawn (the page marks its canvas once pixels other than the background
were rendered), the granulometry curves drawn, the mesh list and the failed mesh. A screenshot is
saved as WORK_DIR/serve.png. Exit 77 (skipped) only when no chromium is installed.

Usage: serve_browser.py MORPHEX DATA_DIR WORK_DIR"""
import html.parser
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serve_common import Server, check, fail, make_index, run  # noqa: E402

SKIP = 77


class Page(html.parser.HTMLParser):
    """What the test reads from the DOM: attributes by element id, the results' and the gallery's
    names, the failures table's text."""

    def __init__(self):
        super().__init__()
        self.by_id, self.results, self.gallery, self.failures = {}, [], [], ""
        self.open = []  # ids of the enclosing elements that matter

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.by_id[a["id"]] = a
        if tag == "body":
            self.by_id["body"] = a
        if tag == "li" and "data-name" in a:
            if "results" in self.open:
                self.results.append(a["data-name"])
            elif "gallery" in self.open:
                self.gallery.append(a["data-name"])
        if tag in ("ol", "ul", "table") and a.get("id") in ("results", "gallery", "failures"):
            self.open.append(a["id"])

    def handle_endtag(self, tag):
        if tag in ("ol", "ul", "table") and self.open:
            self.open.pop()

    def handle_data(self, data):
        if "failures" in self.open:
            self.failures += data


def chromium():
    return os.environ.get("MORPHEX_CHROMIUM") or shutil.which("chromium") or \
        shutil.which("chromium-browser")


def browse(browser, work, url, *action, budget_ms=30000):
    """Chromium headless on `url` (--dump-dom or --screenshot=FILE), its own profile; as root it
    needs --no-sandbox. WebGL comes from SwiftShader, the software renderer, so no GPU is needed."""
    args = [browser, "--headless=new", "--no-sandbox", "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader", "--no-first-run", "--disable-extensions",
            "--user-data-dir=" + os.path.join(work, "profile"), "--window-size=1400,1000",
            "--hide-scrollbars", f"--virtual-time-budget={budget_ms}", *action, url]
    result = subprocess.run(args, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        fail(f"chromium exited {result.returncode}: {result.stderr[-2000:]}")
    return result.stdout


def main():
    morphex, data, work = sys.argv[1:4]
    browser = chromium()
    if not browser:
        print("SKIP: no chromium (scripts/setup installs Debian's chromium)")
        return SKIP
    index, collection = make_index(morphex, data, work)
    expected = [n["name"] for n in json.loads(run(
        [morphex, "query", "--db", index, "tee-1", "-k", "5", "--json"]))["neighbours"]]
    server = Server(morphex, index, "--labels", os.path.join(collection, "labels.cla"))
    try:
        url = server.url + "/#query=tee-1&kind=combined&metric=l1&k=5"
        # Virtual time stands still while requests are pending, so the budget is the page's own
        # work; a loaded machine gets a second, longer try before the page is judged.
        for budget in (30000, 120000):
            page = Page()
            page.feed(browse(browser, work, url, "--dump-dom", budget_ms=budget))
            if page.by_id.get("body", {}).get("data-query") == "done" and \
                    page.by_id.get("view", {}).get("data-rendered") not in (None, "loading"):
                break
        body = page.by_id.get("body", {})
        check(body.get("data-ready") == "true", f"the page did not load the index: {body}")
        message = page.by_id.get("message", {})
        check("hidden" in message, "the page shows an error (see its #message)")
        check(body.get("data-query") == "done", f"the query did not finish: {body}")
        check(page.results == expected, f"results {page.results}, morphex query gives {expected}")
        check(page.by_id["view"].get("data-rendered") == "true",
              f"3D view not drawn: data-rendered={page.by_id['view'].get('data-rendered')}")
        check(page.by_id["curves"].get("data-drawn") == "true", "granulometry curves not drawn")
        check(len(page.gallery) == 12 and "tee-1" in page.gallery, f"gallery: {page.gallery}")
        check("sheet" in page.failures and "bounds no volume" in page.failures,
              f"failures table: {page.failures!r}")
        shot = os.path.join(work, "serve.png")
        browse(browser, work, url, "--screenshot=" + shot)
        check(os.path.getsize(shot) > 10000, "the screenshot is nearly empty")
        server.stop()
    finally:
        server.kill()
    print(f"serve in chromium: query results {page.results}, 3D view and curves drawn; "
          f"screenshot {shot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The documentation's links resolve, and the front page stays short.

Every relative link and image in the top-level Markdown files (README.md, CHANGELOG.md) and in
docs/**/*.md must name a file or directory of the repository, and a link with an anchor into a
Markdown file (`page.md#heading`, or `#heading` within the page) must name one of that page's
headings by GitHub's slug (lower case; punctuation other than `-` and `_` dropped; spaces to `-`;
a repeated heading gets `-1`, `-2`, ...) or an explicit `<a id=...>`/`<a name=...>`.

Links into build/ and post/ are not checked: both are made at run time (setup.sh's build, the
runs' output) and are not part of the repository, so a fresh clone has neither. Links with a
scheme (https:, mailto:) are not followed. Code (fenced blocks, `inline code`) holds no links.

README.md is the front page: at most README_MAX_LINES lines; the rest belongs in docs/."""

import re
import shutil
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
README_MAX_LINES = 220
# made at run time, not in the repository (see the module's docstring)
RUNTIME_DIRS = ("build", "post")


def pages():
    """The Markdown files whose links are checked."""
    return sorted(ROOT.glob("*.md")) + sorted((ROOT / "docs").rglob("*.md"))


FENCE = re.compile(r"^\s{0,3}(`{3,}|~{3,})")
INLINE_CODE = re.compile(r"(`+)(?:(?!\1).)+?\1")
# [text](target "title") and ![alt](target); the text may hold one level of brackets (an image)
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*(<[^>]*>|[^()\s]*(?:\([^()\s]*\)[^()\s]*)*)"
                         r"(?:\s+(?:\"[^\"]*\"|'[^']*'))?\s*\)")
REFERENCE_DEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
HTML_LINK = re.compile(r"<(?:a|img)\s[^>]*?(?:href|src)\s*=\s*\"([^\"]*)\"", re.IGNORECASE)
HTML_ANCHOR = re.compile(r"<a\s[^>]*?(?:id|name)\s*=\s*\"([^\"]*)\"", re.IGNORECASE)
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def outside_fences(text):
    """(line number, line) of the lines outside fenced code blocks."""
    fence = None
    for number, line in enumerate(text.splitlines(), 1):
        m = FENCE.match(line)
        if m:
            if fence is None:
                fence = m.group(1)[0] * len(m.group(1))
            elif m.group(1).startswith(fence):
                fence = None
            continue
        if fence is None:
            yield number, line


def prose_lines(text):
    """(line number, line) outside fenced code blocks, with inline code removed."""
    for number, line in outside_fences(text):
        yield number, INLINE_CODE.sub("", line)


def links(text):
    """(line number, target) of every link and image in a Markdown text. A link's text may run
    over several lines, so inline links are found in the prose as a whole."""
    lines = dict(prose_lines(text))
    prose = "\n".join(lines.get(n, "") for n in range(1, text.count("\n") + 2))
    found = []
    for m in INLINE_LINK.finditer(prose):
        found.append((prose.count("\n", 0, m.start(1)) + 1, m.group(1).strip("<>")))
    for number, line in lines.items():
        m = REFERENCE_DEF.match(line)
        if m:
            found.append((number, m.group(1).strip("<>")))
        for m in HTML_LINK.finditer(line):
            found.append((number, m.group(1)))
    return sorted(found, key=lambda f: f[0])


def slug(heading):
    """GitHub's anchor for a heading's text: the rendered text (code, emphasis and link
    syntax removed), lower case, without characters other than letters, digits, spaces, `-`
    and `_`, spaces turned into `-`."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)   # links and images: their text
    text = re.sub(r"<[^>]+>", "", text)                          # inline HTML
    text = text.replace("`", "")
    text = re.sub(r"(\*+)(\S(?:.*?\S)?)\1", r"\2", text)          # emphasis with *
    text = re.sub(r"(?<!\w)(_+)(\S(?:.*?\S)?)\1(?!\w)", r"\2", text)  # with _, not inside words
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors(path):
    """Every anchor a Markdown file defines: its headings' slugs (repeats numbered as GitHub
    numbers them) and explicit HTML ids."""
    found, seen = set(), {}
    for _, line in outside_fences(path.read_text(encoding="utf-8")):
        h = HEADING.match(line)
        if h:
            base = slug(h.group(2))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else f"{base}-{n}")
        for a in HTML_ANCHOR.finditer(line):
            found.add(a.group(1))
    return found


def problem(page, target, root=ROOT):
    """Why a link from `page` to `target` does not resolve within the repository `root`; None
    when it does (or is not checked)."""
    if not target or SCHEME.match(target) or target.startswith("//"):
        return None
    path_part, _, anchor = target.partition("#")
    path_part = path_part.split("?", 1)[0]
    if path_part.startswith("/"):
        return "absolute path: write links relative to the page"
    resolved = (page.parent / path_part).resolve() if path_part else page.resolve()
    try:
        relative = resolved.relative_to(root)
    except ValueError:
        return "points outside the repository"
    if relative.parts and relative.parts[0] in RUNTIME_DIRS:
        return None
    if not resolved.exists():
        return f"no such file: {relative.as_posix()}"
    if anchor and resolved.is_file() and resolved.suffix.lower() == ".md":
        if anchor not in anchors(resolved):
            return f"no heading with anchor #{anchor} in {relative.as_posix()}"
    return None


def broken_links(paths, root=ROOT):
    """'page:line: target: reason' for every link of `paths` that does not resolve."""
    out = []
    for page in paths:
        for number, target in links(page.read_text(encoding="utf-8")):
            why = problem(page, target, root)
            if why:
                out.append(f"{page.relative_to(root).as_posix()}:{number}: {target}: {why}")
    return out


class Links(unittest.TestCase):
    def test_pages_found(self):
        names = {p.relative_to(ROOT).as_posix() for p in pages()}
        self.assertIn("README.md", names)
        self.assertTrue(any(n.startswith("docs/") for n in names), names)

    def test_every_relative_link_resolves(self):
        broken = broken_links(pages())
        self.assertEqual(broken, [], "broken links:\n" + "\n".join(broken))

    def test_readme_is_short(self):
        lines = (ROOT / "README.md").read_text(encoding="utf-8").count("\n")
        self.assertLessEqual(lines, README_MAX_LINES,
                             f"README.md has {lines} lines; move detail into docs/")


class Checker(unittest.TestCase):
    """The checker itself, on pages in a temporary repository root (root/docs/, root/post/)."""

    def setUp(self):
        self.root = Path(tempfile.mkdtemp(prefix="test_links_")).resolve()
        self.dir = self.root / "docs"
        self.dir.mkdir()

    def tearDown(self):
        shutil.rmtree(self.root)

    def page(self, name, text):
        p = self.dir / name
        p.write_text(text, encoding="utf-8")
        return p

    def test_slugs_as_github_makes_them(self):
        self.assertEqual(slug("Friction that binds, et != en: what the law restitutes and how "
                              "LIGGGHTS follows it"),
                         "friction-that-binds-et--en-what-the-law-restitutes-and-how-liggghts-follows-it")
        self.assertEqual(slug("Every single collision exact (`exactCollision`)"),
                         "every-single-collision-exact-exactcollision")
        self.assertEqual(slug("The 27 → 28 rpm step by window"), "the-27--28-rpm-step-by-window")
        self.assertEqual(slug("**Bold** and [a link](x.md)"), "bold-and-a-link")
        self.assertEqual(slug("tangential_model_pournin"), "tangential_model_pournin")

    def test_finds_broken_files_and_anchors(self):
        self.page("b.md", "# One\n## Two\n## Two\n<a id=\"here\"></a>\n")
        a = self.page("a.md", "\n".join([
            "[ok](b.md) [ok](b.md#one) [ok](b.md#two-1) [ok](b.md#here) [ok](#local)",
            "![ok](b.md) [ok](./) [web](https://example.org/x) [run](../post/x.csv) [run](../build/)",
            "[bad](missing.md) [bad](b.md#three) [bad](#nowhere) [bad](../../outside.md)",
            "![bad](missing.png)",
            "`[not a link](missing.md)`",
            "```", "[not a link](missing.md)", "```",
            "[ref]: missing_too.md",
            "[a link over", "two lines](missing_three.md)",
            "## Local",
        ]) + "\n")
        broken = broken_links([a], self.root)
        targets = [b.split(": ")[1] for b in broken]
        self.assertEqual(targets, ["missing.md", "b.md#three", "#nowhere", "../../outside.md", "missing.png",
                                   "missing_too.md", "missing_three.md"], broken)


if __name__ == "__main__":
    unittest.main()

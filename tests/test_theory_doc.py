"""Every section of docs/theory.md that the repository cites exists as a heading.

The code, tests, validation studies, benchmarks, notebooks and the README cite the theory
document as ``theory.md`` followed by a section sign and a number (also ranges such as 3.2-3.4
and lists such as "4, 7.1"). This test reads those files as text, collects every cited
section number and checks that docs/theory.md has a Markdown heading with that number
("## 4. Title" or "### 3.5 Title"), so that a reader can follow every citation inside the
repository. Only files are read; the package is not imported.
"""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "theory.md"
SCANNED = ("dynstiff", "tests", "validation", "benchmarks", "notebooks", "README.md")

SECTION = "\u00a7"
NUM = r"\d+(?:\.\d+)*"
# "theory.md" (possibly across a line break), a first section, then more sections joined by
# a comma / "and" (each with its own section sign) or a range dash (section sign optional)
CITATION = re.compile(
    r"theory\.md\s*(" + SECTION + r"\s*" + NUM
    + r"(?:(?:\s*[,;]\s*(?:and\s+)?|\s+and\s+)" + SECTION + r"\s*" + NUM
    + r"|\s*(?:-|\u2013|to)\s*" + SECTION + r"?\s*" + NUM + r")*)")
HEADING = re.compile(r"^#+[ \t]+(" + NUM + r")\.?[ \t]", re.MULTILINE)


def _text_files():
    for name in SCANNED:
        path = ROOT / name
        files = [path] if path.is_file() else sorted(p for p in path.rglob("*") if p.is_file())
        for f in files:
            if "__pycache__" in f.parts or ".ipynb_checkpoints" in f.parts:
                continue
            try:
                text = f.read_bytes().decode("utf-8")
            except UnicodeDecodeError:
                continue                                  # binary (figures)
            # notebooks are JSON: a section sign may be stored escaped
            yield f, text.replace("\\u00a7", SECTION)


def _expand(group):
    """Section numbers of one citation group, ranges filled in ("3.2-3.4" -> 3.2, 3.3, 3.4)."""
    out = []
    prev = None
    for sep, num in re.findall(r"(-|\u2013|to|,|;|and|^)?\s*" + SECTION + r"?\s*(" + NUM + r")",
                               group):
        if sep in ("-", "\u2013", "to") and prev is not None:
            a, b = prev.split("."), num.split(".")
            if len(a) == len(b) and a[:-1] == b[:-1] and 0 < int(b[-1]) - int(a[-1]) <= 20:
                stem = ".".join(a[:-1] + [""])
                out += [stem + str(k) for k in range(int(a[-1]) + 1, int(b[-1]))]
        out.append(num)
        prev = num
    return out


def collect_citations():
    """{section: [(relative path, line), ...]} of every citation in the scanned files."""
    found = {}
    for f, text in _text_files():
        for match in CITATION.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            for num in _expand(match.group(1)):
                found.setdefault(num, []).append((str(f.relative_to(ROOT)), line))
    return found


def doc_sections():
    return HEADING.findall(DOC.read_text(encoding="utf-8"))


def test_citation_parser_reads_lists_and_ranges():
    s = SECTION
    got = [_expand(m.group(1)) for m in CITATION.finditer(
        f"(theory.md {s}3.2-3.4) theory.md {s}4, {s}7.1, 2 m; theory.md\n{s}5) "
        f"theory.md {s}4-{s}6 theory.md {s}7.3, 1.0125")]
    assert got == [["3.2", "3.3", "3.4"], ["4", "7.1"], ["5"], ["4", "5", "6"], ["7.3"]]


def test_the_repository_cites_the_theory_document():
    cited = collect_citations()
    assert len(cited) >= 20, f"only {sorted(cited)} found: is the citation pattern still right?"
    assert sum(len(v) for v in cited.values()) >= 100


def test_every_cited_section_is_a_heading_of_docs_theory_md():
    assert DOC.is_file(), f"{DOC.relative_to(ROOT)} is missing"
    sections = set(doc_sections())
    cited = collect_citations()
    assert cited, "no theory.md citation found (the test would pass vacuously)"
    missing = {num: places for num, places in cited.items() if num not in sections}
    lines = [f"  {SECTION}{num}: " + ", ".join(f"{p}:{ln}" for p, ln in places)
             for num, places in sorted(missing.items(),
                                       key=lambda kv: [int(x) for x in kv[0].split(".")])]
    assert not missing, ("citations of theory.md with no heading in docs/theory.md:\n"
                         + "\n".join(lines))


def test_section_headings_are_unique():
    nums = doc_sections()
    dup = sorted({n for n in nums if nums.count(n) > 1})
    assert not dup, f"docs/theory.md numbers these sections twice: {dup}"


def test_docs_theory_md_is_self_contained():
    text = DOC.read_text(encoding="utf-8")
    assert "shared/" not in text
    assert "/work/" not in text
    assert "../" not in text


def test_readme_points_to_the_repository_copy():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "shared/" not in readme and "../" not in readme

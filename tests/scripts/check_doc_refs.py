#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every file, section and option that a doc, a header or source comment, or a
tool's --help names must exist (issue 49 item 5).

- Markdown links [text](path#anchor): the file, and the heading the anchor names.
- Section references, README "Title" / docs/x.md "Title" / x.md "Title": a
  heading of that title in that file (or one it begins, "Exact" for
  "Exact: BVH traversal ...").
- Paths under the project's top folders (src/core/file.c, tests/scripts/):
  the file or folder, in the tracked tree.
- Options after a tool's name on one line of a doc or code block
  (snell-bench --frames 5): an option that tool's --help (or one of its modes'
  --help) lists; and every option of snell-bench's --help on docs/benchmarking.md.
- Every doc's first shell block says how long it takes and what it takes on
  disk: a time (12 min, 90 s) and a size (740 MB, "nothing on disk") in the
  block's comments or a paragraph of its section that begins "How long".

Usage: check_doc_refs.py SOURCE_DIR [snell-render snell-bench snell-kiosk]
(tools left out or not built: their options are not checked)."""
import os, re, subprocess, sys

root = sys.argv[1]
tools = {os.path.basename(p): p for p in sys.argv[2:] if os.path.exists(p)}
# Paths of other projects' trees that comments cite (Mesa's drivers)
FOREIGN = ("src/broadcom/", "src/gallium/", "src/freedreno/", "src/panfrost/", "src/mesa/", "src/compiler/")
TOP = ("src", "include", "ports", "tests", "docs", "bench", "scripts", "cmake", "shaders_es", "tools", "examples")
problems = []


def tracked():
    out = subprocess.run(["git", "-C", root, "ls-files", "-co", "--exclude-standard"], capture_output=True,
                         text=True)
    if out.returncode == 0 and out.stdout:
        return [l for l in out.stdout.splitlines() if os.path.exists(os.path.join(root, l))]
    found = []
    for d, dirs, files in os.walk(root):
        dirs[:] = [x for x in dirs if not x.startswith(".") and not x.startswith("build")]
        found += [os.path.relpath(os.path.join(d, f), root) for f in files]
    return found


files = tracked()
fileset = set(files)
dirset = {os.path.dirname(f) for f in files}
for f in list(dirset):
    while f:
        f = os.path.dirname(f)
        dirset.add(f)


def slug(title):
    s = re.sub(r"[^\w\- ]", "", title.strip().lower())
    return s.replace(" ", "-")


_headings = {}


def headings(path):
    """Titles and GitHub anchors of a markdown file's headings (code blocks skipped)."""
    if path not in _headings:
        titles, anchors, fence = set(), set(), False
        seen = {}
        with open(os.path.join(root, path), encoding="utf-8") as f:
            for line in f:
                if line.lstrip().startswith("```"):
                    fence = not fence
                    continue
                m = re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
                if m and not fence:
                    t = m.group(1)
                    titles.add(t.replace("`", ""))
                    a = slug(t)
                    n = seen.get(a, 0)
                    seen[a] = n + 1
                    anchors.add(a if n == 0 else "%s-%d" % (a, n))
        _headings[path] = (titles, anchors)
    return _headings[path]


def doc_path(name, near):
    """The markdown file a section reference names, relative to root."""
    if name == "README":
        return "README.md"
    for cand in (name, os.path.normpath(os.path.join(os.path.dirname(near), name)), os.path.join("docs", name)):
        if cand in fileset:
            return cand
    return None


def check_text(path, text, is_md):
    fence = False
    for no, line in enumerate(text.splitlines(), 1):
        where = "%s:%d" % (path, no)
        if is_md and line.lstrip().startswith("```"):
            fence = not fence
        # markdown links (docs only; inline code aside)
        if is_md:
            bare = re.sub(r"`[^`]*`", "", line)
            for m in re.finditer(r"\]\(([^)\s]+)\)", bare):
                target = m.group(1)
                if re.match(r"[a-z]+:", target):
                    continue
                file_part, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                if dest not in fileset and dest not in dirset:
                    problems.append("%s: link to %s: no such file" % (where, target))
                elif anchor and dest.endswith(".md") and anchor not in headings(dest)[1]:
                    problems.append("%s: link to %s: %s has no such section" % (where, target, dest))
        # README "Title", docs/x.md "Title" (quotes may be escaped in C strings)
        for m in re.finditer(r'\b(README|[\w/.-]+\.md)(?:\.md)? \\?"([^"\\]+)\\?"', line):
            doc = doc_path(m.group(1), path)
            if not doc:
                problems.append('%s: %s "%s": no such file' % (where, m.group(1), m.group(2)))
            elif not any(t == m.group(2) or re.match(re.escape(m.group(2)) + r"\W", t) for t in headings(doc)[0]):
                problems.append('%s: %s has no section "%s"' % (where, doc, m.group(2)))
        # paths under the project's top folders
        for m in re.finditer(r"(?<![\w./$-])((?:%s)/[\w./+-]*[\w/])" % "|".join(TOP), line):
            p = m.group(1)
            # a pattern (src/methods/<name>.c), a path in another project's tree
            # (Mesa's src/broadcom/), or no path at all (src/desc/out)
            if re.search(r"[<>*{}$]", line[m.start():m.end() + 1]) or p.startswith(FOREIGN):
                continue
            if not p.endswith("/") and "." not in os.path.basename(p):
                continue
            q = p.rstrip("/")
            if q not in fileset and q not in dirset:
                problems.append("%s: %s: no such file or folder" % (where, p))
        # options after a tool's name
        if tools and (is_md or path.endswith((".c", ".h", ".sh", ".cmake"))):
            for m in re.finditer(r"\b(snell-render|snell-bench|snell-kiosk)\b((?:\s+[^\s`|;&)]+)*)", line):
                opts = known.get(m.group(1))
                if opts is None:
                    continue
                for o in re.findall(r"(?<![\w-])(--[a-z0-9][a-z0-9-]*)", m.group(2)):
                    if o not in opts:
                        problems.append("%s: %s %s: not an option of %s (--help)" % (where, m.group(1), o,
                                                                                      m.group(1)))


def help_options(exe):
    """The options a tool's --help lists, with those of its modes: an option
    the usage lines name or "--X --help" points to, whose own --help begins
    "usage: TOOL --X"."""
    name = os.path.basename(exe)
    out = subprocess.run([exe, "--help"], capture_output=True, text=True).stdout
    opts = set(re.findall(r"(?<![\w-])(--[a-z0-9][a-z0-9-]*)", out))
    usage = out.split("\n\n", 1)[0]
    modes = set(re.findall(r"(?<![\w-])(--[a-z0-9][a-z0-9-]*)", usage)) | set(re.findall(r"(--[a-z0-9-]+) --help", out))
    texts = [out]
    for o in sorted(modes):
        sub = subprocess.run([exe, o, "--help"], capture_output=True, text=True).stdout
        if sub.startswith("usage: %s %s" % (name, o)):
            texts.append(sub)
    for t in texts[1:]:
        opts |= set(re.findall(r"(?<![\w-])(--[a-z0-9][a-z0-9-]*)", t))
    return opts, "\n".join(texts)


known = {}
helps = {}
for name, exe in tools.items():
    known[name], helps[name] = help_options(exe)

for f in files:
    if f.endswith(".md") or (f.startswith(("include/", "src/", "ports/")) and f.endswith((".c", ".h", ".cpp"))):
        if f.startswith("bench/notes/") or f.startswith("tests/data/"):
            continue  # history: it names what was, as it was
        with open(os.path.join(root, f), encoding="utf-8", errors="replace") as fh:
            check_text(f, fh.read(), f.endswith(".md"))
for name, text in helps.items():
    check_text("%s --help" % name, text, False)

# a page that documents every option of a tool's --help (modes apart)
COMPLETE = {"snell-bench": "docs/benchmarking.md"}
for name, doc in COMPLETE.items():
    if name in tools and doc in fileset:
        with open(os.path.join(root, doc), encoding="utf-8") as fh:
            text = fh.read()
        main_help = helps[name].split("\n" + "usage: ", 1)[0]
        for o in sorted(set(re.findall(r"(?<![\w-])(--[a-z0-9][a-z0-9-]*)", main_help))):
            if not re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(o), text):
                problems.append("%s: %s --help lists %s, the page does not" % (doc, name, o))

TIME = re.compile(r"\b\d+(?:\.\d+)?(?:\s*[-–]\s*\d+(?:\.\d+)?)?\s*(?:s|min|h|hours?|minutes?)\b")
DISK = re.compile(r"\b\d+(?:\.\d+)?\s*(?:KB|MB|GB|KiB|MiB|GiB)\b|nothing on disk")
for doc in sorted(f for f in files if f == "README.md" or (f.startswith("docs/") and f.endswith(".md"))):
    with open(os.path.join(root, doc), encoding="utf-8") as fh:
        lines = fh.read().splitlines()
    start = next((i for i, l in enumerate(lines) if l.strip() in ("```sh", "```bash", "```shell")), None)
    if start is None:
        continue
    close = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("```")), len(lines))
    end = next((i for i in range(close, len(lines)) if lines[i].startswith("#")), len(lines))
    # the block's comments, and a paragraph of its section that begins "How long"
    paragraphs = re.split(r"\n\s*\n", "\n".join(lines[close + 1:end]))
    span = "\n".join(lines[start:close] + [t for t in paragraphs if t.lstrip().startswith("How long")])
    if not TIME.search(span) or not DISK.search(span):
        problems.append("%s:%d: its first command says no %s" % (
            doc, start + 1, " and no ".join(w for w, r in (("time", TIME), ("disk", DISK)) if not r.search(span))))

for p in problems:
    print(p)
print("%d dangling reference(s) in %d files and %d --help texts" % (len(problems), len(files), len(helps)))
sys.exit(1 if problems else 0)

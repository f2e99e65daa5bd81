#!/usr/bin/python3
"""Every path a documentation page names exists: the README, docs/*.md and the scenes' README files.

Usage: scripts/check_doc_paths.py [ROOT]   (ROOT: the checkout, default this script's parent folder;
exits 1 listing each page's missing paths, 0 when there are none — the suite's
Docs.EveryPathAPageNamesExists)

A path is a word that starts with one of the tree's top folders (apps/, core/, docs/, experiments/,
illum/, scenes/, scripts/, shaders/, tests/, traverse/, voxelize/, cmake/, .ci/) or ../shared/. It
exists when it names a file or folder from ROOT, or from ROOT/shaders (a shader named by its path from
the shader root, as the code includes it), with or without ".glsl" (a shader named by its stage,
"value_mip.comp"). "stem.{h,cpp}" names both files. Not checked: templates (a path followed by "<",
"NAME" or "*": "scenes/leak-walls/wall-<k>v.json", "illum/methods/NAME.cpp"), paths in the history
that say where they went ("git show REV:path", "removed in REV" on the same line), and ../shared/
where ROOT/../shared is absent (the test scenes are not part of a checkout).
"""
import glob
import os
import re
import sys

TOP = r"(?:apps|core|docs|experiments|illum|scenes|scripts|shaders|tests|traverse|voxelize|cmake|\.ci)"
PATH = re.compile(r"(?<![A-Za-z0-9_./-])((?:\.\./shared/)?" + TOP + r"/[A-Za-z0-9_./+-]*)")
HISTORY = re.compile(r"git show [0-9a-f]+[~^0-9]*:|removed in [0-9a-f]{7}|since removed")


def pages(root):
    found = ["README.md"] + sorted(glob.glob("docs/**/*.md", root_dir=root, recursive=True))
    found += sorted(glob.glob("scenes/**/*.md", root_dir=root, recursive=True))
    return [p for p in found if os.path.isfile(os.path.join(root, p))]


def expand(path, rest):
    """The paths a match names: "core/flip" + ".{h,cpp}…" is core/flip.h and core/flip.cpp."""
    m = re.match(r"(\.?)\{([A-Za-z0-9_.,]+)\}", rest)
    if not m:
        return [path]
    return [path + m.group(1) + alt for alt in m.group(2).split(",")]


def exists(root, path):
    path = path.rstrip(".,;:)")
    for base in (root, os.path.join(root, "shaders")):
        full = os.path.normpath(os.path.join(base, path))
        if os.path.exists(full) or os.path.exists(full + ".glsl"):
            return True
    return False


def missing_paths(root):
    shared = os.path.isdir(os.path.join(root, "..", "shared"))
    out = {}
    for page in pages(root):
        with open(os.path.join(root, page), encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                if HISTORY.search(line):
                    continue
                for m in PATH.finditer(line):
                    path, rest = m.group(1), line[m.end():]
                    if rest[:1] in ("<", "*") or "NAME" in path or rest.startswith("NAME"):
                        continue
                    if path.startswith("../shared/") and not shared:
                        continue
                    for p in expand(path, rest):
                        if not exists(root, p):
                            out.setdefault(page, []).append(f"{number}: {p.rstrip('.,;:)')}")
    return out


def main():
    if len(sys.argv) > 2:
        print("usage: check_doc_paths.py [ROOT]", file=sys.stderr)
        sys.exit(2)
    root = sys.argv[1] if len(sys.argv) == 2 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    if not os.path.isdir(root):
        print(f"check_doc_paths.py: error: ROOT '{root}': not a folder", file=sys.stderr)
        sys.exit(2)
    bad = missing_paths(root)
    for page, paths in bad.items():
        print(f"{page} names {len(paths)} path(s) that do not exist:")
        for p in paths:
            print(f"  line {p}")
    if bad:
        sys.exit(1)
    print(f"check_doc_paths.py: every path named by {len(pages(root))} pages exists")


if __name__ == "__main__":
    main()

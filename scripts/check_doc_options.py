#!/usr/bin/python3
"""Every option a vgi command's help prints is named on that command's manual page (issue "A front page,
a manual and a results page": the help text and the manual agree).

Usage: scripts/check_doc_options.py VGI [ROOT]   (VGI: the vgi binary; ROOT: the checkout, default this
script's parent folder; exits 1 listing each page's missing options, 0 when there are none — the
suite's Docs.EveryCommandOptionIsOnItsManualPage)

An option is a `--word` in `vgi COMMAND --help`; it is named when the page holds `--word` not followed
by another letter, digit or hyphen. The pages: render, voxelize and info in docs/rendering.md; diff,
compare and sweep in docs/metrics.md; view in docs/viewer.md. (Every method's parameters are
docs/PARAMETERS.md, checked by Docs.ParametersPageIsCurrent.)
"""
import os
import re
import subprocess
import sys

PAGES = {
    "render": "docs/rendering.md",
    "voxelize": "docs/rendering.md",
    "info": "docs/rendering.md",
    "diff": "docs/metrics.md",
    "compare": "docs/metrics.md",
    "sweep": "docs/metrics.md",
    "view": "docs/viewer.md",
}
OPTION = re.compile(r"(?<![A-Za-z0-9-])--[a-z][a-z0-9-]*")


def missing(vgi, root):
    found = {}
    for command, page in PAGES.items():
        helptext = subprocess.run([vgi, command, "--help"], capture_output=True, text=True, check=True).stdout
        with open(os.path.join(root, page), encoding="utf-8") as f:
            text = f.read()
        for option in sorted(set(OPTION.findall(helptext)) - {"--help"}):
            if not re.search(re.escape(option) + r"(?![A-Za-z0-9-])", text):
                found.setdefault(page, []).append(f"vgi {command} {option}")
    return found


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    vgi = sys.argv[1]
    if not os.access(vgi, os.X_OK):
        print(f"check_doc_options.py: VGI '{vgi}' is not an executable file", file=sys.stderr)
        return 2
    root = sys.argv[2] if len(sys.argv) == 3 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    found = missing(vgi, root)
    for page, options in found.items():
        print(f"{page} does not name: {', '.join(options)}")
    if not found:
        print(f"check_doc_options.py: every option of {len(PAGES)} commands is on its manual page")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())

"""What every measurement script a reader is told to run does with its arguments and with `vgi`'s
failures, written once: arguments are checked up front (exit 2, naming the argument and the value), a
failed `vgi` command is reported with the reason vgi gave (its "vgi: error: …" line), and a user's
mistake never ends in a Python traceback.

    import script_args as sa
    def main(): a = ap.parse_args(); sa.vgi_binary("--vgi", a.vgi); …
    if __name__ == "__main__": sa.run_main(main)
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys

PROG = os.path.basename(sys.argv[0])


class UsageError(Exception):
    """A user's mistake: the argument, its value and why; run_main prints it and exits 2."""

    def __init__(self, arg, value, why):
        super().__init__(f"{arg} '{value}': {why}")


def fail(arg, value, why):
    raise UsageError(arg, value, why)


class ArgumentParser(argparse.ArgumentParser):
    """argparse that exits 2 with its message (as argparse does) and names the script."""

    def error(self, message):
        self.print_usage(sys.stderr)
        print(f"{PROG}: error: {message}", file=sys.stderr)
        sys.exit(2)


def vgi_binary(arg, path):
    """`path` is a runnable vgi (a file, executable)."""
    if not os.path.exists(path):
        fail(arg, path, "does not exist (build it: bash scripts/build.sh, then build/apps/vgi)")
    if os.path.isdir(path):
        fail(arg, path, "is a folder, not the vgi program")
    if not os.access(path, os.X_OK):
        fail(arg, path, "is not executable")
    return path


def folder_with(arg, path, *files):
    """`path` is a folder holding each of `files` (what an earlier step wrote there)."""
    if not os.path.exists(path):
        fail(arg, path, "does not exist")
    if not os.path.isdir(path):
        fail(arg, path, "is not a folder")
    for f in files:
        if not os.path.isfile(os.path.join(path, f)):
            fail(arg, path, f"has no {f} (is it the output folder of the step that writes it?)")
    return path


def sweep_results(arg, folder, experiment=None):
    """The results.json of a `vgi sweep` output folder, checked: it parses, has rows, and (when
    `experiment` is given) is a sweep of that experiment."""
    folder_with(arg, folder, "results.json")
    try:
        with open(os.path.join(folder, "results.json")) as f:
            res = json.load(f)
    except ValueError as e:
        fail(arg, folder, f"its results.json does not parse ({e})")
    if not isinstance(res, dict) or not isinstance(res.get("rows"), list) or not res["rows"]:
        fail(arg, folder, "its results.json has no rows (did the sweep finish? `vgi sweep … --collect`)")
    if experiment and res.get("experiment") != experiment:
        fail(arg, folder, f"is a sweep of '{res.get('experiment')}', not of scenes/experiments/{experiment}.json")
    return res


def mean_sd(values):
    """The mean and the sample standard deviation (0 for one value) of the numbers among values
    (None, None for none); values that are all equal give that value and 0 exactly, no rounding."""
    v = [x for x in values if x is not None]
    if not v:
        return None, None
    if all(x == v[0] for x in v):
        return v[0], 0.0
    m = sum(v) / len(v)
    return m, math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))


def number(x):
    """A metric as a float, or None where it has no value: vgi writes "undefined" for a ratio with no
    value (against a black reference; core/json_text.h), older files may hold null, and a row may lack
    the metric altogether."""
    return float(x) if isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) else None


def fmt(x, spec=".4f", missing="—"):
    """A metric as a table cell: `missing` where there is none (None: no such row or field), "undefined"
    where vgi wrote one without a value, else the number formatted with `spec`."""
    if x is None:
        return missing
    v = number(x)
    return "undefined" if v is None else format(v, spec)


def out_folder(arg, path):
    """`path` is a folder this script may write into (made if missing)."""
    if os.path.exists(path) and not os.path.isdir(path):
        fail(arg, path, "exists and is not a folder")
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as e:
        fail(arg, path, f"cannot be made: {e.strerror}")
    if not os.access(path, os.W_OK):
        fail(arg, path, "is not writable")
    return path


def positive_int(arg, value):
    try:
        n = int(value)
    except (TypeError, ValueError):
        fail(arg, value, "expected a positive whole number")
    if n <= 0:
        fail(arg, value, "expected a positive whole number")
    return n


def size(arg, value):
    """WxH, both positive."""
    m = re.fullmatch(r"([1-9][0-9]{0,4})x([1-9][0-9]{0,4})", str(value))
    if not m:
        fail(arg, value, "expected WIDTHxHEIGHT, e.g. 256x256")
    return value


def vgi_reason(output):
    """The reason a vgi command gave: its last "vgi: error: …" line, else its last non-empty line."""
    lines = [line for line in output.splitlines() if line.strip()]
    errors = [line for line in lines if "vgi: error:" in line]
    return (errors or lines or ["(no output)"])[-1].strip()


class VgiFailed(Exception):
    """A vgi command this script ran failed; the message holds the command and vgi's reason."""


def run_vgi(cmd, log=None):
    """Runs `cmd` (a vgi command line). Its output goes to `log` (a path) when given. Raises VgiFailed
    with vgi's own reason when it exits non-zero."""
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    if log:
        with open(log, "w") as f:
            f.write(p.stdout)
    if p.returncode != 0:
        raise VgiFailed(f"{' '.join(cmd)}\n  exit {p.returncode}: {vgi_reason(p.stdout)}")
    return p.stdout


def run_main(main):
    """Runs main() and exits with its status; a user's mistake (a bad argument, a file that cannot be
    read or written, a failed vgi command) is one line on stderr, never a traceback."""
    try:
        rc = main()
    except UsageError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        sys.exit(2)
    except VgiFailed as e:
        print(f"{PROG}: FAILED: {e}", file=sys.stderr)
        sys.exit(1)
    except OSError as e:
        where = f" '{e.filename}'" if e.filename else ""
        print(f"{PROG}: error:{where} {e.strerror or e}", file=sys.stderr)
        sys.exit(2)
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        sys.exit(130)
    sys.exit(rc or 0)

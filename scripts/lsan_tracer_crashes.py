#!/usr/bin/env python3
"""The failed tests of a ctest JUnit file (ctest --output-junit) whose only fault is LeakSanitizer's own
tracer crashing at the process's exit ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal
error": the checker stopping the world under load, not a report on the code), one name per line, for
scripts/test_sanitizers.sh to run once more. Exits 1, listing nothing, when any failed test has another
fault (a sanitizer's report, a failed assertion, a timeout): those are never retried.
  python3 scripts/lsan_tracer_crashes.py JUNIT.xml
"""
import sys
import xml.etree.ElementTree as ET

CRASH = "LeakSanitizer has encountered a fatal error"
TRACER = "Tracer caught signal"
# What a real finding prints (ASan, LSan's leak report, UBSan), or a test's own failure.
REPORTS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer: detected memory leaks", "runtime error:",
           "SUMMARY: UndefinedBehaviorSanitizer", "[  FAILED  ]", "Failure\n", "Timeout")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: lsan_tracer_crashes.py JUNIT.xml")
    try:
        root = ET.parse(sys.argv[1]).getroot()
    except (OSError, ET.ParseError) as e:
        sys.exit(f"lsan_tracer_crashes.py: {sys.argv[1]}: {e}")
    retry = []
    for case in root.iter("testcase"):
        if case.get("status") not in ("fail", "failed") and case.find("failure") is None:
            continue
        out = "".join(e.text or "" for e in case.iter() if e.tag in ("system-out", "failure"))
        if CRASH in out and TRACER in out and not any(r in out for r in REPORTS):
            retry.append(case.get("name"))
        else:
            print(f"lsan_tracer_crashes.py: {case.get('name')} failed otherwise: not retried", file=sys.stderr)
            sys.exit(1)
    print("\n".join(retry))


if __name__ == "__main__":
    main()

"""Prints one closing line "N passed, N failed, N skipped" over all JUnit XML files in a folder.

Before it: each failed or skipped test with the reason, and when real data sets are missing (the
tests say "<set> missing: run scripts/get_test_data.sh ..."), the command that gets them.
Exits 1 when a test failed or when no test ran at all (an empty run must not look green).
"""
import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

MISSING_SET = re.compile(r"(\w+) missing: run scripts/get_test_data\.sh")
# gtest's lines before the message: "file:line", and "Failed" for ADD_FAILURE() and FAIL().
HEADER = re.compile(r"^(\S+:\d+|Failed)$")


def reason(element: ET.Element) -> str:
    """The first line of a failure or skip message that is not one of gtest's header lines."""
    text = (element.get("message") or "") + "\n" + (element.text or "")
    lines = [l.strip() for l in text.splitlines() if l.strip() and not HEADER.match(l.strip())]
    return lines[0][:300] if lines else ""


def main(folder: str) -> int:
    passed = failed = skipped = 0
    missing_sets = set()
    for path in sorted(Path(folder).rglob("*.xml")):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as err:
            print(f"unreadable test result {path}: {err}")
            failed += 1
            continue
        for case in root.iter("testcase"):
            name = f"{case.get('classname')}.{case.get('name')}"
            problem = case.find("failure")
            if problem is None:
                problem = case.find("error")
            if problem is not None:
                failed += 1
                print(f"failed: {name}: {reason(problem)}")
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
                note = case.find("skipped")
                print(f"skipped: {name}" + (f": {reason(note)}" if note is not None else ""))
            else:
                passed += 1
                continue
            missing_sets.update(MISSING_SET.findall(ET.tostring(case, encoding="unicode")))
    if missing_sets:
        sets = " ".join(sorted(missing_sets))
        print(f"real data missing: {sets}; get it with: bash scripts/get_test_data.sh {sets}")
    print(f"{passed} passed, {failed} failed, {skipped} skipped")
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))

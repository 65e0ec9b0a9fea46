#!/usr/bin/env python3
"""Counts the JUnit results of gtest and rostest under a test_results directory.

Prints every failure and ends with the line "N passed, N failed". A suite listed in
the expected-suites file that left no result (a crash, a timeout) counts as failed.
Exit status 0 only if nothing failed."""
import pathlib
import sys
import xml.etree.ElementTree as ET


def main():
    results = pathlib.Path(sys.argv[1])
    expected = []
    if len(sys.argv) > 2 and pathlib.Path(sys.argv[2]).exists():
        expected = [l.strip() for l in pathlib.Path(sys.argv[2]).read_text().splitlines()
                    if l.strip() and not l.startswith('#')]
    passed = failed = 0
    seen = set()
    for xml in sorted(results.rglob('*.xml')):
        seen.add(xml.stem)
        try:
            root = ET.parse(xml).getroot()
        except ET.ParseError as e:
            print(f'FAILED {xml.name}: unreadable result file ({e})')
            failed += 1
            continue
        cases = root.iter('testcase')
        for case in cases:
            name = f"{case.get('classname')}.{case.get('name')}"
            bad = case.find('failure') is not None or case.find('error') is not None
            if case.find('skipped') is not None or case.get('status') == 'notrun':
                continue
            if bad:
                failed += 1
                msg = (case.find('failure') if case.find('failure') is not None else case.find('error'))
                print(f'FAILED {name}: {(msg.get("message") or msg.text or "").strip()[:400]}')
            elif not xml.name.startswith('rostest-'):
                # A passing rostest case is the launch of a test node whose own cases
                # are in its rosunit-*.xml: count those, not the launch again.
                passed += 1
    for suite in expected:
        if not any(s.endswith(suite) for s in seen):
            print(f'FAILED {suite}: no result file (the test binary crashed, timed out or was not built)')
            failed += 1
    print(f'{passed} passed, {failed} failed')
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == '__main__':
    sys.exit(main())

#!/usr/bin/env python3
"""Counts the JUnit results of gtest, rostest and the Python tests under a test_results directory.

Usage: count_test_results.py RESULTS_DIR [EXPECTED_SUITES_FILE] [--without FEATURE ...]

Prints every failure and every skipped test case with its reason, and ends with the line
"N passed, N failed, N skipped". A suite listed in the expected-suites file that left no
result (a crash, a timeout) counts as failed; a line "[feature] suite" is expected only when
the build has that feature (--without lcm: built with -DBEARING_SIM_WITH_LCM=OFF).
Exit status 0 only if nothing failed and something passed."""
import argparse
import pathlib
import sys
import xml.etree.ElementTree as ET


def expected_suites(path, without):
    """(suite, feature or None) of the expected-suites file, less the features built without."""
    suites = []
    for line in pathlib.Path(path).read_text().splitlines():
        line = line.strip()
        if not line or line.startswith('#'):
            continue
        feature = None
        if line.startswith('['):
            feature, line = line[1:].split(']', 1)
            line = line.strip()
        suites.append((line, feature))
    return [(s, f) for s, f in suites if f not in without]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('results')
    p.add_argument('expected', nargs='?')
    p.add_argument('--without', action='append', default=[], help='a feature the build does not have')
    a = p.parse_args()
    results = pathlib.Path(a.results)
    expected = expected_suites(a.expected, set(a.without)) if a.expected and pathlib.Path(a.expected).exists() else []
    passed = failed = skipped = 0
    seen = set()
    for xml in sorted(results.rglob('*.xml')):
        seen.add(xml.stem)
        try:
            root = ET.parse(xml).getroot()
        except ET.ParseError as e:
            print(f'FAILED {xml.name}: unreadable result file ({e})')
            failed += 1
            continue
        for case in root.iter('testcase'):
            name = f"{case.get('classname')}.{case.get('name')}"
            bad = case.find('failure') if case.find('failure') is not None else case.find('error')
            skip = case.find('skipped')
            if skip is not None or case.get('status') == 'notrun':
                reason = (skip.get('message') or skip.text or '').strip() if skip is not None else 'not run'
                print(f'SKIPPED {name}: {reason[:200]}')
                skipped += 1
            elif bad is not None:
                failed += 1
                print(f'FAILED {name}: {(bad.get("message") or bad.text or "").strip()[:400]}')
            elif not xml.name.startswith('rostest-'):
                # A passing rostest case is the launch of a test node whose own cases
                # are in its rosunit-*.xml: count those, not the launch again.
                passed += 1
    for suite, _ in expected:
        if not any(s.endswith(suite) for s in seen):
            print(f'FAILED {suite}: no result file (the test binary crashed, timed out or was not built)')
            failed += 1
    for feature in sorted(set(a.without)):
        print(f'SKIPPED the suites marked [{feature}] in the expected-suites file: built without {feature}')
    print(f'{passed} passed, {failed} failed, {skipped} skipped')
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == '__main__':
    sys.exit(main())

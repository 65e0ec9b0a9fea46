"""dev/cwru_coverage.py: a real record is judged against the campaign runs of its own class, and
a feature is outside when its median over the record's windows lies beyond the class's 1st-99th
percentiles, which for a known distribution are known in closed form."""
import sys

import numpy as np
import pytest

from conftest import SOURCE

sys.path.insert(0, str(SOURCE / 'dev'))
import cwru_coverage  # noqa: E402

Z99 = 2.3263  # the standard normal's 99th percentile


def campaign(runs=20000, seed=3):
    """Two classes: 'none' with x ~ N(0, 1), 'ball' with x ~ N(10, 1); y ~ U(0, 1) for both."""
    rng = np.random.default_rng(seed)
    features, labels = [], []
    for label, mean in (('none', 0.0), ('ball', 10.0)):
        for x, y in zip(rng.normal(mean, 1.0, runs), rng.uniform(0.0, 1.0, runs)):
            features.append({'x': x, 'y': y})
            labels.append(label)
    return features, labels


def record(number, truth, xs, y=0.5):
    return {'record': number, 'truth': truth, 'windows': [{'x': x, 'y': y} for x in xs]}


def test_a_feature_is_outside_beyond_its_own_class_percentiles():
    features, labels = campaign()
    records = [record(1, 'none', [2.0, 2.1, 2.2]),            # inside N(0, 1)'s +-2.33
               record(2, 'none', [2.3, 2.5, 9.0]),            # median 2.5: outside
               record(3, 'ball', [10.0, 2.5, 10.5]),          # median 10: inside its own class
               record(4, 'ball', [5.0, 5.0, 5.0], y=1.2)]     # x and y outside the ball runs'
    found = {number: beyond for number, _, beyond in cwru_coverage.outside(['x', 'y'], features, labels, records)}
    assert found[1] == [] and found[3] == []
    (name, value, low, high), = found[2]
    assert name == 'x' and value == 2.5
    # The sample percentiles of 20000 draws are within ~0.04 of the closed form (their standard
    # error is sqrt(p (1 - p) / n) / pdf(z) = 0.028).
    assert low == pytest.approx(-Z99, abs=0.1) and high == pytest.approx(Z99, abs=0.1)
    assert [n for n, *_ in found[4]] == ['x', 'y']
    (_, _, y_low, y_high) = found[4][1]
    assert y_low == pytest.approx(0.01, abs=0.005) and y_high == pytest.approx(0.99, abs=0.005)


def test_the_report_counts_each_feature_and_record():
    features, labels = campaign(runs=2000)
    records = [record(1, 'none', [5.0]), record(2, 'none', [0.0]), record(3, 'ball', [0.0], y=-1.0)]
    found = cwru_coverage.outside(['x', 'y'], features, labels, records)
    lines = cwru_coverage.report(['x', 'y'], found, len(records))
    assert any(line.startswith('| x | 2 / 3 | 1: 5 (') and '3: 0 (' in line for line in lines)
    assert any(line.startswith('| y | 1 / 3 | 3: -1 (') for line in lines)
    assert lines[-1] == 'Records with none outside: 1 / 3.'

"""Where the real records lie outside what a campaign shows of their class: for each real record
and feature, the median over its windows against the campaign runs of the record's own class,
between their LOW and HIGH percentiles. A learner trained on the campaign has never seen a
value beyond them in that class, so what it does there is extrapolation (issue 30: a virtual
sensor is worth what a pipeline tuned on it does on the machine). Used by
dev/cwru_classifier_check.py --coverage; tested in test/python/test_cwru_coverage.py."""
import numpy as np

LOW, HIGH = 1.0, 99.0  # percentiles: 1 % of a class's runs on either side are let through


def outside(names, train_features, train_labels, records, low=LOW, high=HIGH):
    """[(record, truth, [(name, value, range_low, range_high), ...])]: each record's features whose
    median over its windows lies outside its class's [low, high] percentiles in the campaign."""
    labels = np.asarray(train_labels)
    table = np.array([[f[n] for n in names] for f in train_features], dtype=float)
    ranges = {c: np.percentile(table[labels == c], [low, high], axis=0) for c in set(train_labels)}
    result = []
    for r in records:
        lo, hi = ranges[r['truth']]
        median = np.median([[w[n] for n in names] for w in r['windows']], axis=0)
        beyond = [(n, float(v), float(a), float(b)) for n, v, a, b in zip(names, median, lo, hi) if not a <= v <= b]
        result.append((r['record'], r['truth'], beyond))
    return result


def report(names, found, records_total):
    """Markdown lines: per feature, how many records lie outside and which (value, the class's
    range); then how many features each record has outside."""
    lines = ['| feature | records outside their class | which: value (campaign range) |', '|---|---|---|']
    for name in names:
        hits = [(record, value, a, b) for record, _, beyond in found for n, value, a, b in beyond if n == name]
        if hits:
            which = ', '.join(f'{record}: {value:.3g} ({a:.3g} - {b:.3g})' for record, value, a, b in hits)
            lines.append(f'| {name} | {len(hits)} / {records_total} | {which} |')
    counts = sorted(((len(beyond), record, truth) for record, truth, beyond in found), reverse=True)
    lines += ['', 'Features outside per record: ' + ', '.join(f'{record} ({truth}) {n}' for n, record, truth in counts
                                                              if n) + '.',
              f'Records with none outside: {sum(1 for n, _, _ in counts if not n)} / {records_total}.']
    return lines

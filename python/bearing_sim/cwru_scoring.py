"""Scoring of the analyser's verdict on CWRU records against their known fault (RULES), and the
counts and confusion matrix of a set of scored records. Used by bearing_sim.cwru_benchmark."""

RULES = """\
Scoring:
- Verdict: the analyser's result['verdict'] (outcome none / fault / ambiguous, and the kinds
  it names) when the result has one; otherwise derived from the series: outcome "none" when
  no series is suspected, else "fault" naming the suspected kinds.
- Class of a record: "none" (nothing found); the single kind named ("outer", "inner",
  "ball", "cage"); "ambiguous(a|b)" when the analyser cannot tell between the kinds listed;
  "multiple" when it asserts two or more kinds.
- Right type alone: the class equals the record's fault kind; a normal record is right when
  its class is "none".
- Wrong type named: the outcome is "fault" and names a kind other than the record's (on a
  normal record: any kind), alone or beside the right one.
- Cannot tell: an ambiguous outcome is neither right nor wrong; it is counted apart, as
  "truth among them" or "truth not among them" (the cannot_tell column).
- A record whose file cannot be read or analysed is an error row, in no count but its own.
"""

SHORT = {'outer race': 'outer', 'inner race': 'inner', 'ball': 'ball', 'cage': 'cage', 'none': 'none'}
KIND_ORDER = ('outer', 'inner', 'ball', 'cage')
TRUTHS = ('none', 'inner race', 'ball', 'outer race')  # the table's faults, in CWRU's order
FIXED_CLASSES = ('none',) + KIND_ORDER + ('multiple',)
COUNT_KEYS = ('records', 'right_alone', 'wrong_named', 'cannot_tell_truth_among', 'cannot_tell_truth_not_among',
              'none', 'errors')


def short_kind(kind):
    """'outer race' -> 'outer' (short names pass through)."""
    if kind in SHORT:
        return SHORT[kind]
    if kind in SHORT.values():
        return kind
    raise ValueError(f'unknown fault kind {kind!r}')


def verdict_of(result):
    """The verdict of an analyze() result: {'outcome', 'kinds', 'text', 'source'}; source
    'analyser' when the result carries one, 'derived' from the suspected series otherwise."""
    given = result.get('verdict')
    if given is not None:
        return dict(outcome=given['outcome'], kinds=list(given.get('kinds', [])), text=given.get('text', ''),
                    source='analyser')
    kinds = [f['fault'] for f in result['faults'] if f['suspected']]
    return dict(outcome='fault' if kinds else 'none', kinds=kinds, source='derived',
                text=f"suspected: {', '.join(kinds)}" if kinds else 'nothing suspected')


def classify(verdict):
    """The class of a verdict: none, outer, inner, ball, cage, ambiguous(a|b) or multiple."""
    outcome = verdict['outcome']
    kinds = sorted({short_kind(k) for k in verdict['kinds']}, key=KIND_ORDER.index)
    if outcome == 'none':
        return 'none'
    if not kinds:
        raise ValueError(f'verdict {outcome!r} names no fault kind')
    if outcome == 'ambiguous':
        return f"ambiguous({'|'.join(kinds)})"
    if outcome == 'fault':
        return kinds[0] if len(kinds) == 1 else 'multiple'
    raise ValueError(f'unknown verdict outcome {outcome!r}')


def score(truth, verdict):
    """A record's scores: {'class', 'right_alone' (0/1), 'wrong_named' (0/1), 'cannot_tell'
    ('', 'truth among', 'truth not among')}. truth: the table's fault ('none', 'outer race', ...)."""
    true_kind = short_kind(truth)
    cls = classify(verdict)
    kinds = {short_kind(k) for k in verdict['kinds']}
    cannot_tell = ''
    if verdict['outcome'] == 'ambiguous':
        cannot_tell = 'truth among' if true_kind in kinds else 'truth not among'
    wrong = verdict['outcome'] == 'fault' and bool(kinds - {true_kind})
    return {'class': cls, 'right_alone': int(cls == true_kind), 'wrong_named': int(wrong), 'cannot_tell': cannot_tell}


def counts(rows):
    """COUNT_KEYS over scored rows (dicts with 'error' and score()'s keys)."""
    c = dict.fromkeys(COUNT_KEYS, 0)
    for r in rows:
        c['records'] += 1
        if r['error']:
            c['errors'] += 1
            continue
        c['right_alone'] += r['right_alone']
        c['wrong_named'] += r['wrong_named']
        c['cannot_tell_truth_among'] += r['cannot_tell'] == 'truth among'
        c['cannot_tell_truth_not_among'] += r['cannot_tell'] == 'truth not among'
        c['none'] += r['class'] == 'none'
    return c


def counts_by_fault(rows):
    """{'all': counts, <fault>: counts of its records} for the faults present."""
    by_fault = {'all': counts(rows)}
    for fault in TRUTHS:
        mine = [r for r in rows if r['fault'] == fault]
        if mine:
            by_fault[fault] = counts(mine)
    return by_fault


def confusion(rows):
    """Truth (rows) x class (columns) over the rows without error; the fixed classes, then
    the ambiguous ones that occur."""
    scored = [r for r in rows if not r['error']]
    columns = list(FIXED_CLASSES) + sorted({r['class'] for r in scored} - set(FIXED_CLASSES))
    truths = [short_kind(t) for t in TRUTHS]
    matrix = [[sum(1 for r in scored if short_kind(r['fault']) == t and r['class'] == c) for c in columns]
              for t in truths]
    return {'rows': truths, 'columns': columns, 'counts': matrix}


def summarise(rows):
    """Counts of all records, of the fan-end records (their own bearing and channel), of those
    Smith & Randall graded (their SKF drive-end records), per grade group of theirs, and the
    confusion matrix."""
    graded = [r for r in rows if r['smith_randall_group']]
    fan_end = [r for r in rows if r.get('channel') == 'FE']
    return {'scoring': RULES,
            'all': counts_by_fault(rows),
            'fan_end': counts_by_fault(fan_end) if fan_end else {},
            'graded_skf': counts_by_fault(graded),
            'smith_randall_groups': {g: counts([r for r in graded if r['smith_randall_group'] == g]) for g in 'YPN'},
            'confusion': confusion(rows)}

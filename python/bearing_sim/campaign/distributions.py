"""Distributions of campaign parameters, drawn for run i from (campaign seed, i, parameter
name) alone: every draw is a SHA-256 of those three, so run i never depends on other runs,
on the order of the parameters, on the machine or on the numpy version."""
import hashlib
import math
import statistics

from .errors import CampaignError

KINDS = ('choice', 'uniform', 'log_uniform', 'normal', 'integer', 'grid')


def unit_draw(seed, index, name):
    """A number in (0, 1) from (seed, index, name): the midpoint of one of 2^64 equal cells."""
    digest = hashlib.sha256(f'{seed}:{index}:{name}'.encode()).digest()
    return (int.from_bytes(digest[:8], 'big') + 0.5) / 2.0**64


class Distribution:
    """One parameter: a plain value (constant), or a mapping with exactly one of KINDS."""

    def __init__(self, name, spec, path):
        self.name = name
        self.where = f"{path}: key 'parameters.{name}"  # the closing quote comes with the sub-key
        if not isinstance(spec, dict):
            self.kind, self.value = 'constant', spec
            return
        if len(spec) != 1 or next(iter(spec)) not in KINDS:
            raise CampaignError(f"{self.where}': expected a value or one of {{{', '.join(KINDS)}: ...}}, "
                                f"got keys {sorted(spec)}")
        self.kind, args = next(iter(spec.items()))
        getattr(self, '_check_' + self.kind)(args)

    def _error(self, message):
        return CampaignError(f"{self.where}.{self.kind}': {message}")

    def _bounds(self, args, positive=False):
        if (not isinstance(args, list) or len(args) != 2
                or not all(isinstance(a, (int, float)) and not isinstance(a, bool) and math.isfinite(a)
                           for a in args)):
            raise self._error(f'expected [low, high] (two finite numbers), got {args!r}')
        low, high = float(args[0]), float(args[1])
        if not low < high:
            raise self._error(f'expected low < high, got [{args[0]}, {args[1]}]')
        if positive and not low > 0.0:
            raise self._error(f'a log-uniform range must be positive, got low = {args[0]}')
        return low, high

    def _check_choice(self, args):
        if not isinstance(args, list) or not args:
            raise self._error(f'expected a non-empty list of values, got {args!r}')
        self.values = args

    _check_grid = _check_choice

    def _check_uniform(self, args):
        self.low, self.high = self._bounds(args)

    def _check_log_uniform(self, args):
        self.low, self.high = self._bounds(args, positive=True)

    def _check_integer(self, args):
        if not isinstance(args, list) or len(args) != 2 or not all(isinstance(a, int) and not isinstance(a, bool)
                                                                   for a in args) or args[0] > args[1]:
            raise self._error(f'expected [low, high] (integers, low <= high, both included), got {args!r}')
        self.low, self.high = args

    def _check_normal(self, args):
        keys = {'mean', 'std', 'min', 'max'}
        if not isinstance(args, dict) or set(args) - keys or not {'mean', 'std'} <= set(args):
            raise self._error(f'expected {{mean, std, min, max}} (min and max optional), got {args!r}')
        for k, v in args.items():
            if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
                raise CampaignError(f"{self.where}.normal.{k}': expected a finite number, got {v!r}")
        self.mean, self.std = float(args['mean']), float(args['std'])
        if not self.std > 0.0:
            raise CampaignError(f"{self.where}.normal.std': must be > 0, got {args['std']}")
        self.min, self.max = float(args.get('min', -math.inf)), float(args.get('max', math.inf))
        if not self.min < self.max:
            raise CampaignError(f"{self.where}.normal': expected min < max, got min {self.min}, max {self.max}")
        dist = statistics.NormalDist(self.mean, self.std)
        self.cdf_low, self.cdf_high = dist.cdf(self.min), dist.cdf(self.max)
        if not self.cdf_high - self.cdf_low > 1e-12:
            raise CampaignError(f"{self.where}.normal': [min, max] holds no probability of this normal "
                                f'(more than 7 standard deviations from the mean)')
        self.dist = dist

    def grid_size(self):
        return len(self.values) if self.kind == 'grid' else 1

    def draw(self, seed, index, grid_index=0):
        """The value of run `index`; grid parameters take `grid_index` (from the campaign)."""
        if self.kind == 'constant':
            return self.value
        if self.kind == 'grid':
            return self.values[grid_index]
        u = unit_draw(seed, index, self.name)
        if self.kind == 'choice':
            return self.values[min(int(u * len(self.values)), len(self.values) - 1)]
        if self.kind == 'uniform':
            return self.low + u * (self.high - self.low)
        if self.kind == 'log_uniform':
            return math.exp(math.log(self.low) + u * (math.log(self.high) - math.log(self.low)))
        if self.kind == 'integer':
            return self.low + min(int(u * (self.high - self.low + 1)), self.high - self.low)
        # Truncated normal by the inverse CDF of the truncated range.
        x = self.dist.inv_cdf(self.cdf_low + u * (self.cdf_high - self.cdf_low))
        return min(max(x, self.min), self.max)

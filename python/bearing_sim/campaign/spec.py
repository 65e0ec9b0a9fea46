"""A campaign file (docs/datasets.md, "Campaigns"): N runs of one scenario template whose
${parameters} are drawn from distributions. Run i is defined by (campaign, i) alone."""
import hashlib
import json
import os
import re

import yaml

from . import strict_yaml
from .distributions import Distribution, unit_draw
from .errors import CampaignError
from .substitution import References, fill

FORMATS = ('npy', 'hdf5')
MAX_SCENARIO_SEED = 1000000  # the core reads integers of a scenario file up to this
# Run files are numbered with 7 digits (run_0000042.npy), so that their names sort by index.
MAX_COUNT = 10_000_000
_TOP_KEYS = {'name', 'description', 'count', 'seed', 'format', 'label_rate_hz', 'parameters', 'scenario'}
_NAME = re.compile(r'[A-Za-z0-9_.-]+')


class RunDefinition:
    """What run i is: its parameters, its scenario (YAML text and the source name it resolves
    against) and the files derived from the campaign's bearing/sensor overrides."""

    def __init__(self, index, parameters, scenario, derived_files):
        self.index = index
        self.parameters = parameters  # name -> value
        self.scenario = scenario      # dict, bearing_file/sensor_file as written or derived
        self.derived_files = derived_files  # scenario key -> (file name, YAML text)


class Campaign:
    def __init__(self, text, path):
        self.path = os.path.abspath(path)
        self.text = text
        self.directory = os.path.dirname(self.path)
        doc = strict_yaml.load(text, path)
        if not isinstance(doc, dict):
            raise CampaignError(f'{path}: expected a mapping with the keys {sorted(_TOP_KEYS)}')
        unknown = sorted(set(doc) - _TOP_KEYS)
        if unknown:
            raise CampaignError(f"{path}: key '{unknown[0]}': unknown key (allowed: {', '.join(sorted(_TOP_KEYS))})")
        self.definition_sha256 = hashlib.sha256(json.dumps(doc, sort_keys=True, default=str).encode()).hexdigest()
        self.name = self._required(doc, 'name', str)
        if not _NAME.fullmatch(self.name):
            raise CampaignError(f"{path}: key 'name': letters, digits, '.', '-' and '_' only, got {self.name!r}")
        self.description = doc.get('description', '')
        self.count = self._required(doc, 'count', int)
        if not 1 <= self.count <= MAX_COUNT:
            raise CampaignError(f"{path}: key 'count': must be 1 to {MAX_COUNT:,} (run files are numbered with "
                                f'7 digits), got {self.count:,}')
        self.seed = doc.get('seed', 0)
        if not isinstance(self.seed, int) or isinstance(self.seed, bool) or self.seed < 0:
            raise CampaignError(f"{path}: key 'seed': expected an integer >= 0, got {self.seed!r}")
        self.format = doc.get('format', 'npy')
        if self.format not in FORMATS:
            raise CampaignError(f"{path}: key 'format': expected one of {', '.join(FORMATS)}, got {self.format!r}")
        self.label_rate_hz = doc.get('label_rate_hz', 10.0)
        if not isinstance(self.label_rate_hz, (int, float)) or isinstance(self.label_rate_hz, bool) \
                or not self.label_rate_hz > 0:
            raise CampaignError(f"{path}: key 'label_rate_hz': expected a number > 0, got {self.label_rate_hz!r}")
        parameters = doc.get('parameters') or {}
        if not isinstance(parameters, dict):
            raise CampaignError(f"{path}: key 'parameters': expected a mapping of name: distribution")
        for name in parameters:
            if not isinstance(name, str) or not re.fullmatch(r'[A-Za-z_][A-Za-z0-9_]*', name):
                raise CampaignError(f"{path}: key 'parameters.{name}': a parameter name is a Python-style identifier")
        self.parameters = {n: Distribution(n, s, path) for n, s in parameters.items()}
        self.grid = [d for d in self.parameters.values() if d.kind == 'grid']
        self.template = doc.get('scenario')
        if not isinstance(self.template, dict):
            raise CampaignError(f"{path}: key 'scenario': required, a scenario (docs/scenarios.md) whose values "
                                f'may be ${{parameter}}')
        self.references = References(self.parameters, self.template, path)

    @classmethod
    def load(cls, path):
        return cls(strict_yaml.read_text(path, 'campaign file'), path)

    def _required(self, doc, key, kind):
        if key not in doc:
            raise CampaignError(f"{self.path}: key '{key}': required")
        value = doc[key]
        if not isinstance(value, kind) or isinstance(value, bool):
            raise CampaignError(f"{self.path}: key '{key}': expected {kind.__name__}, got {value!r}")
        return value

    # -- run i -------------------------------------------------------------------------
    def check_index(self, index):
        if not 0 <= index < self.count:
            raise CampaignError(f'{self.path}: run {index} does not exist (count: {self.count}, runs 0..{self.count - 1})')

    def grid_indices(self, index):
        """Grid parameters form a Cartesian product (the last varying fastest), cycled over i."""
        out, rest = {}, index
        for d in reversed(self.grid):
            out[d.name] = rest % d.grid_size()
            rest //= d.grid_size()
        return out

    def parameters_of(self, index):
        self.check_index(index)
        grid = self.grid_indices(index)
        return {n: d.draw(self.seed, index, grid.get(n, 0)) for n, d in self.parameters.items()}

    def run_seed(self, index):
        """The scenario seed of run i when the template gives none, in the range a scenario
        file accepts (0 to 1,000,000)."""
        return int(unit_draw(self.seed, index, '#seed') * (MAX_SCENARIO_SEED + 1))

    def definition(self, index):
        # The manifest records each parameter with the ${...} inside its value filled in.
        parameters = self.references.resolve(self.parameters_of(index))
        scenario = fill(self.template, parameters, 'scenario', self.path)
        scenario.setdefault('name', f'{self.name}_{index:07d}')
        scenario.setdefault('seed', self.run_seed(index))
        derived = {}
        for key, folder in (('bearing_file', 'bearings'), ('sensor_file', 'sensors')):
            spec = scenario.get(key)
            if isinstance(spec, dict):
                derived[key] = (key.replace('_file', '.yaml'), self._derived_file(spec, key, folder))
            elif isinstance(spec, str):
                scenario[key] = self.resolve(spec, folder, key)
        return RunDefinition(index, parameters, scenario, derived)

    def resolve(self, name, folder, key):
        """A bearing or sensor file as the core finds it: absolute, relative to the campaign's
        directory, or in its sibling ../bearings (../sensors)."""
        for candidate in (name, os.path.join(self.directory, name),
                          os.path.join(self.directory, os.pardir, folder, name)):
            if os.path.isabs(candidate) and os.path.isfile(candidate):
                return os.path.normpath(candidate)
        raise CampaignError(f"{self.path}: key 'scenario.{key}': no file {name!r} (absolute, next to the campaign, "
                            f'or in ../{folder})')

    def _derived_file(self, spec, key, folder):
        """{file: NAME, set: {dotted.key: value}}: the file with those keys replaced."""
        if set(spec) - {'file', 'set'} or 'file' not in spec:
            raise CampaignError(f"{self.path}: key 'scenario.{key}': expected a file name or "
                                f'{{file: NAME, set: {{dotted.key: value}}}}, got keys {sorted(spec)}')
        path = self.resolve(spec['file'], folder, key + '.file')
        doc = strict_yaml.load(strict_yaml.read_text(path, folder[:-1] + ' file'), path)
        for dotted, value in (spec.get('set') or {}).items():
            node, parts = doc, str(dotted).split('.')
            for part in parts[:-1]:
                if not isinstance(node.get(part, {}), dict):
                    raise CampaignError(f"{self.path}: key 'scenario.{key}.set.{dotted}': '{part}' in "
                                        f'{path} is not a mapping')
                node = node.setdefault(part, {})
            node[parts[-1]] = value
        return yaml.safe_dump(doc, sort_keys=False)


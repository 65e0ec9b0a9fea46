"""${name} references of a campaign: checked once when the file is read (unknown names, a
parameter that refers to itself, a value or a run's scenario that would grow beyond the size
limit of a configuration file once filled in), then filled in for each run."""
import copy
import re

from .errors import CampaignError
from .strict_yaml import MAX_BYTES

REF = re.compile(r'\$\{([A-Za-z_][A-Za-z0-9_]*)\}')
_FLOAT_BYTES = 25  # repr of a drawn float: at most 24 characters ('-1.2345678901234567e-308'), and a separator


class References:
    """The references between the parameters (name -> Distribution) and from the template.
    Sizes are upper bounds in bytes of YAML text (strict_yaml.expanded_bytes' measure), taking
    for a choice or grid its largest value, so that no run can exceed them."""

    def __init__(self, parameters, template, path):
        self.parameters, self.path = parameters, path
        self._bytes = {}  # name -> bound of the value with its references filled in
        self.order = []   # every parameter after those it refers to: the order to fill them in
        for name in parameters:
            self._parameter_bytes(name, [])
        self._check_size(self._node_bytes(template, 'scenario', []), 'scenario', "a run's scenario")

    def _error(self, key, message):
        return CampaignError(f"{self.path}: key '{key}': {message}")

    def _check_size(self, size, key, what):
        if size > MAX_BYTES:
            raise self._error(key, f'with its ${{...}} filled in, {what} can take {size} bytes, more than '
                                   f'{MAX_BYTES} (1 MiB, the size limit of a configuration file)')

    def _parameter_bytes(self, name, chain):
        if name in self._bytes:
            return self._bytes[name]
        if name in chain:
            cycle = ' -> '.join(f'${{{n}}}' for n in chain[chain.index(name):] + [name])
            raise self._error(f'parameters.{chain[-1]}', f'parameters refer to each other in a circle: {cycle}')
        chain = chain + [name]
        d = self.parameters[name]
        if d.kind == 'constant':
            size = self._node_bytes(d.value, f'parameters.{name}', chain)
        elif d.kind in ('choice', 'grid'):
            size = max(self._node_bytes(v, f'parameters.{name}.{d.kind}[{i}]', chain) for i, v in enumerate(d.values))
        elif d.kind == 'integer':
            size = max(len(str(d.low)), len(str(d.high))) + 1
        else:
            size = _FLOAT_BYTES
        self._check_size(size, f'parameters.{name}', 'the value')
        self._bytes[name] = size
        self.order.append(name)
        return size

    def _node_bytes(self, node, key, chain):
        if isinstance(node, dict):
            return 1 + sum(len(str(k)) + 1 + self._node_bytes(v, f'{key}.{k}', chain) for k, v in node.items())
        if isinstance(node, list):
            return 1 + sum(self._node_bytes(v, f'{key}[{i}]', chain) for i, v in enumerate(node))
        if not isinstance(node, str):
            return len(str(node)) + 1
        names = REF.findall(node)
        for name in names:
            if name not in self.parameters:
                raise self._error(key, f"unknown parameter ${{{name}}} (parameters: {', '.join(self.parameters) or 'none'})")
        if REF.fullmatch(node):
            return self._parameter_bytes(names[0], chain)
        return len(REF.sub('', node)) + 1 + sum(self._parameter_bytes(n, chain) - 1 for n in names)

    def resolve(self, drawn):
        """The parameters of a run with the references inside their values filled in."""
        resolved = {}
        for name in self.order:
            resolved[name] = fill(drawn[name], resolved, f'parameters.{name}', self.path)
        return resolved


def fill(node, values, key, path):
    """A copy of `node` with each '${name}' replaced by values[name] (references already filled
    in): a whole value takes the value with its type (a number, a list, a mapping), a reference
    inside a longer text its text."""
    if isinstance(node, dict):
        return {k: fill(v, values, f'{key}.{k}', path) for k, v in node.items()}
    if isinstance(node, list):
        return [fill(v, values, f'{key}[{i}]', path) for i, v in enumerate(node)]
    if not isinstance(node, str):
        return node
    whole = REF.fullmatch(node)
    if whole:
        return copy.deepcopy(values[whole.group(1)])

    def text(match):
        value = values[match.group(1)]
        if isinstance(value, (dict, list)):
            raise CampaignError(f"{path}: key '{key}': ${{{match.group(1)}}} is a list or mapping and cannot "
                                f'be part of a text')
        return str(value)
    return REF.sub(text, node)

"""YAML as the core reads it (src/core/yaml_reader.hpp): a regular file of at most 1 MiB, and
a key written twice in one mapping refused naming the file, the key and both lines (PyYAML
silently keeps the last occurrence)."""
import os

import yaml

from .errors import CampaignError

MAX_BYTES = 1 << 20  # as the core's configuration files; /dev/zero would be read forever


class _DuplicateKeyError(Exception):
    def __init__(self, key, first_line, line):
        super().__init__(key)
        self.key, self.first_line, self.line = key, first_line, line


class _StrictLoader(yaml.SafeLoader):
    def construct_mapping(self, node, deep=False):
        lines = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=True)
            line = key_node.start_mark.line + 1
            try:
                if key in lines:
                    raise _DuplicateKeyError(key, lines[key], line)
                lines[key] = line
            except TypeError:  # a list or mapping as a key: the safe loader refuses it
                pass
        return super().construct_mapping(node, deep)


def load(text, source):
    """The document of `text`; malformed YAML or a key twice is a CampaignError naming `source`."""
    try:
        return yaml.load(text, Loader=_StrictLoader)  # noqa: S506 (a SafeLoader)
    except _DuplicateKeyError as e:
        raise CampaignError(f"{source}: key '{e.key}' appears twice (lines {e.first_line} and {e.line}); "
                            'remove one') from None
    except yaml.YAMLError as e:
        raise CampaignError(f'{source}: not valid YAML: {e}') from None


def read_text(path, what):
    """The text of the configuration file `path` (`what` names it in errors)."""
    if not os.path.isfile(path):
        raise CampaignError(f'{path}: cannot read the {what}: '
                            + ('not a regular file' if os.path.exists(path) else 'no such file'))
    try:
        if os.path.getsize(path) > MAX_BYTES:
            raise CampaignError(f'{path}: {what} larger than 1 MiB, refused')
        with open(path, encoding='utf-8') as f:
            return f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise CampaignError(f'{path}: cannot read the {what}: {getattr(e, "strerror", None) or e}') from None

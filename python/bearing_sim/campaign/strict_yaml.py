"""YAML as the core reads it (src/core/yaml_reader.hpp): a regular file of at most 1 MiB, and
a key written twice in one mapping refused naming the file, the key and both lines (PyYAML
silently keeps the last occurrence). Aliases may not expand a document beyond what 1 MiB of
text holds (a "billion laughs" file is 1 kB), nor may an alias contain itself."""
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


class _AliasError(Exception):
    pass


def expanded_bytes(node, memo):
    """About the length of the node's text with every alias written out in full (a scalar and its
    separator, one byte per list or mapping); an alias is counted once per use, computed once."""
    key = id(node)
    if key in memo:
        if memo[key] is None:
            raise _AliasError(f'an alias contains itself (line {node.start_mark.line + 1})')
        return memo[key]
    memo[key] = None  # in progress: met again below means the node contains itself
    if isinstance(node, yaml.ScalarNode):
        size = len(node.value) + 1
    elif isinstance(node, yaml.SequenceNode):
        size = 1 + sum(expanded_bytes(child, memo) for child in node.value)
    else:
        size = 1 + sum(expanded_bytes(k, memo) + expanded_bytes(v, memo) for k, v in node.value)
    memo[key] = size
    return size


def load(text, source):
    """The document of `text`; malformed YAML, a key twice or aliases that expand it beyond
    MAX_BYTES are a CampaignError naming `source`."""
    loader = _StrictLoader(text)  # noqa: S506 (a SafeLoader)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        size = expanded_bytes(node, {})
        if size > MAX_BYTES:
            raise _AliasError(f'its aliases expand it to {size} bytes, more than {MAX_BYTES} (1 MiB, the size limit '
                              f'of a configuration file)')
        return loader.construct_document(node)
    except _DuplicateKeyError as e:
        raise CampaignError(f"{source}: key '{e.key}' appears twice (lines {e.first_line} and {e.line}); "
                            'remove one') from None
    except _AliasError as e:
        raise CampaignError(f'{source}: refused: {e}') from None
    except RecursionError:
        raise CampaignError(f'{source}: refused: lists or mappings nested too deeply to read') from None
    except yaml.YAMLError as e:
        raise CampaignError(f'{source}: not valid YAML: {e}') from None
    finally:
        loader.dispose()


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

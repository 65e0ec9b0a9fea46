"""Shared pieces of the Python tests: paths into the source tree and small campaign files.
Run by the test command (cmake/python.cmake) against the devel space."""
import os
import pathlib

import pytest
import yaml

SOURCE = pathlib.Path(__file__).resolve().parents[2]
BEARINGS = SOURCE / 'config' / 'bearings'
SCENARIOS = SOURCE / 'config' / 'scenarios'


def tool_path():
    """bearing_tool of the devel space this test runs against."""
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep):
        candidate = pathlib.Path(prefix) / 'lib' / 'bearing_sim' / 'bearing_tool'
        if candidate.is_file():
            return candidate
    raise RuntimeError('bearing_tool not found under CMAKE_PREFIX_PATH: source the devel space first')


def small_campaign(count=20, duration_s=0.2, fmt='npy', **overrides):
    """A campaign of short runs of the 6205-like bearing over every kind of distribution."""
    doc = {
        'name': 'small',
        'count': count,
        'seed': 11,
        'format': fmt,
        'parameters': {
            'speed_rpm': {'uniform': [900.0, 1800.0]},
            'radial_load_N': {'normal': {'mean': 1200.0, 'std': 300.0, 'min': 600.0, 'max': 2000.0}},
            'unbalance_kg': {'log_uniform': [1e-4, 1e-3]},
            'position_deg': {'grid': [0.0, 120.0]},
            'width_mm': {'choice': [0.5, 1.0]},
            'defects': {'choice': [[], [{'type': 'spall', 'at_s': 0.05, 'surface': 'outer_race',
                                          'position_deg': '${position_deg}', 'width_mm': '${width_mm}',
                                          'depth_um': 10.0}]]},
        },
        'scenario': {
            'duration_s': duration_s,
            'bearing_file': 'deep_groove_6205.yaml',
            'speed': {'initial_speed_rpm': '${speed_rpm}'},
            'load': {'initial': {'force_N': ['${radial_load_N}', 0.0, 0.0]},
                     'unbalance': {'mass_kg': '${unbalance_kg}', 'radius_m': 0.02, 'phase_deg': 0.0}},
            'defects': '${defects}',
        },
    }
    doc.update(overrides)
    return doc


@pytest.fixture
def campaign_file(tmp_path):
    """Writes a campaign dict into a campaigns/ directory beside a bearings/ link, as the
    shipped config/ tree is laid out, and returns its path."""
    campaigns = tmp_path / 'config' / 'campaigns'
    campaigns.mkdir(parents=True)
    (tmp_path / 'config' / 'bearings').symlink_to(BEARINGS)
    (tmp_path / 'config' / 'sensors').symlink_to(SOURCE / 'config' / 'sensors')

    def write(doc, name='campaign.yaml'):
        path = campaigns / name
        path.write_text(yaml.safe_dump(doc, sort_keys=False) if isinstance(doc, dict) else doc)
        return path
    return write

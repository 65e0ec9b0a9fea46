"""bearing_sim for Python: the ROS-free core (bearing_sim._core, pybind11) with helpers that
take files or dicts, and dataset campaigns (bearing_sim.campaign). docs/python.md.

In the catkin devel space this package shares its directory with the generated messages
(bearing_sim.msg, bearing_sim.srv): catkin's __init__ extends the path to this source
directory and runs this file."""
import os as _os
from pkgutil import extend_path as _extend_path

import yaml as _yaml

# A process that has this directory first on sys.path (a Dask worker started by spawn
# inherits the devel shim's path) still finds the compiled core and the messages.
__path__ = _extend_path(__path__, __name__)

from bearing_sim._core import (Bearing, ConfigError, DivergenceError, InvalidInputError,  # noqa: F401
                               LoadNotCarriedError, cpu_model_name, modes, simd_target_name)
from bearing_sim import _core

__all__ = ['Bearing', 'ConfigError', 'DivergenceError', 'InvalidInputError', 'LoadNotCarriedError',
           'load_bearing', 'static_equilibrium', 'frequencies', 'simulate', 'generate', 'analyze', 'modes',
           'cpu_model_name', 'simd_target_name', 'yaml_text']


def yaml_text(data):
    """YAML text of a dict of plain values (numpy scalars and arrays become numbers and lists)."""
    return _yaml.safe_dump(_plain(data), sort_keys=False)


def _plain(value):
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if hasattr(value, 'tolist'):  # numpy scalar or array
        return _plain(value.tolist())
    return value


def load_bearing(bearing):
    """A Bearing from a file path, a dict with the keys of a bearing file
    (docs/bearing_file.md), or a Bearing (returned as it is)."""
    if isinstance(bearing, Bearing):
        return bearing
    if isinstance(bearing, dict):
        return Bearing.from_yaml(yaml_text(bearing), '<dict>')
    return Bearing.from_file(_os.fspath(bearing))


def static_equilibrium(bearing, force_N=(0.0, 0.0, 0.0), moment_Nm=(0.0, 0.0), cage_angle_rad=0.0):
    """Static equilibrium: displacement (x, y, z, theta_x, theta_y), 5x5 stiffness, ball loads."""
    return load_bearing(bearing).static(list(force_N), list(moment_Nm), cage_angle_rad)


def frequencies(bearing, ring_speed_rad_s):
    """Cage, ball-pass and ball-spin frequencies at a speed of the configured rotating ring."""
    return load_bearing(bearing).frequencies(ring_speed_rad_s)


def simulate(bearing, force_N, ring_speed_rad_s, moment_Nm=(0.0, 0.0), duration_s=1.0, sample_rate_hz=10000.0,
             substeps=0, integrator="adams_pec", allow_long_run=False):
    """A fixed-load, fixed-speed dynamic run from the static equilibrium (bearing_tool simulate).
    integrator: adams_pec (default), adams_pece, etdrk4 or rk4 (docs/model.md, section 10).
    sample_rate_hz at most 1e6; a run estimated (from a short probe) to take over an hour is
    refused unless allow_long_run=True (bearing_tool's --allow-long-run); Ctrl-C stops it.
    Returns time_s, displacement and acceleration (samples x 5) and the run's summary."""
    return load_bearing(bearing).simulate(list(force_N), ring_speed_rad_s, list(moment_Nm), duration_s,
                                          sample_rate_hz, substeps, integrator, allow_long_run)


def generate(scenario, seed=None, duration_s=None, label_rate_hz=10.0, base_dir=None, allow_long_run=False):
    """Runs a scenario (a file path or a dict with the keys of docs/scenarios.md) exactly as
    `bearing_tool generate`. A dict's relative bearing and sensor files resolve against
    base_dir (default: the working directory), else its ../bearings and ../sensors.
    duration_s (default: the scenario's) at most 1e7 s, as a scenario file's; a run estimated to
    take over an hour is refused unless allow_long_run=True (--allow-long-run); Ctrl-C stops it.
    Returns vibration (measured, float32 samples x 3), vibration_ideal, labels and info."""
    if isinstance(scenario, dict):
        text = yaml_text(scenario)
        source = _os.path.join(_os.path.abspath(base_dir or _os.getcwd()), '<dict>.yaml')
    else:
        # Read by the core as bearing_tool reads it: a file that is no regular file, over 1 MiB
        # or not YAML (binary) is a ConfigError naming it.
        source, text = _os.fspath(scenario), None
    return _core.generate_from_yaml(text, source, seed, duration_s, label_rate_hz, allow_long_run)


def analyze(signal, sample_rate_hz, bearing, inner_rad_s=0.0, outer_rad_s=0.0, window_s=0.0, resonance_hz=0.0,
            band_width_hz=2000.0):
    """Condition indicators, envelope spectrum and diagnosis of an acceleration signal (m/s^2,
    1-D) recorded at these ring speeds (bearing_tool analyze; docs/health.md)."""
    return _core.analyze(load_bearing(bearing), signal, sample_rate_hz, inner_rad_s, outer_rad_s, window_s,
                         resonance_hz, band_width_hz)

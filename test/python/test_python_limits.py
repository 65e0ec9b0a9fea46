"""The Python API refuses what bearing_tool refuses, with the same limits (issue 31, items
6-8): the sample rate (1e6 Hz), a scenario's duration (1e7 s), a run estimated over an hour
without allow_long_run=True (--allow-long-run); and Ctrl-C stops a long run promptly."""
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

import bearing_sim
from conftest import BEARINGS

B6205 = BEARINGS / 'deep_groove_6205.yaml'


def scenario(duration_s=1.0):
    return {'name': 'limits', 'duration_s': duration_s, 'seed': 1, 'bearing_file': str(B6205),
            'speed': {'initial_speed_rpm': 1200.0}, 'load': {'initial': {'force_N': [1000.0, 0.0, 0.0]}}}


def test_simulate_refuses_a_sample_rate_above_the_cli_limit():
    b = bearing_sim.load_bearing(B6205)
    with pytest.raises(bearing_sim.InvalidInputError, match=r'sample_rate_hz 1e\+09: at most 1e\+06 Hz'):
        bearing_sim.simulate(b, [1000.0, 0.0, 0.0], ring_speed_rad_s=100.0, duration_s=0.01, sample_rate_hz=1e9)
    # The limit itself is allowed (a short run).
    r = bearing_sim.simulate(b, [1000.0, 0.0, 0.0], ring_speed_rad_s=100.0, duration_s=1e-4, sample_rate_hz=1e6)
    assert len(r['time_s']) == 100


def test_simulate_refuses_a_run_of_hours_without_allow_long_run():
    b = bearing_sim.load_bearing(B6205)
    start = time.monotonic()
    with pytest.raises(bearing_sim.InvalidInputError,
                       match=r'bearing_sim\.simulate: 1e\+09 samples .* measured on this machine: about .*'
                             r'more than 1 hours.*allow_long_run=True'):
        # 1e9 samples (the most a run holds) of 1000 integration steps each (the most a run may
        # take): about 4 days here (AMD EPYC, AVX-512), still hours on a machine 50 times faster.
        bearing_sim.simulate(b, [1000.0, 0.0, 0.0], ring_speed_rad_s=100.0, duration_s=1e5, substeps=1000)
    assert time.monotonic() - start < 30.0  # the probe only, nothing allocated for the run


def test_generate_refuses_a_duration_above_a_scenario_files_limit():
    with pytest.raises(bearing_sim.InvalidInputError, match=r'duration 1e\+09 s: at most 1e\+07 s'):
        bearing_sim.generate(scenario(), duration_s=1e9)
    # The scenario file's own cap (ConfigError naming the key), unchanged.
    with pytest.raises(bearing_sim.ConfigError, match=r'duration_s.*at most 1e7'):
        bearing_sim.generate(scenario(duration_s=1e8))


def test_generate_on_a_file_that_is_not_yaml_is_a_config_error_naming_it(tmp_path):
    # Bytes that are no UTF-8 raised UnicodeDecodeError from Python's own open().read().
    binary = tmp_path / 'binary.yaml'
    binary.write_bytes(bytes(range(256)) * 8)
    with pytest.raises(bearing_sim.ConfigError, match=str(binary)):
        bearing_sim.generate(binary)
    # Not a regular file (it was read until memory ran out), and no file: named as well.
    for path in ('/dev/zero', str(tmp_path / 'missing.yaml')):
        with pytest.raises(bearing_sim.ConfigError, match=path):
            bearing_sim.generate(path)


def test_generate_refuses_a_run_of_hours_without_allow_long_run():
    start = time.monotonic()
    with pytest.raises(bearing_sim.InvalidInputError,
                       match=r'bearing_sim\.generate: 1e\+11 samples .*more than 1 hours.*allow_long_run=True'):
        # 1e11 samples, the longest duration a scenario may have: years at any speed.
        bearing_sim.generate(scenario(), duration_s=1e7)
    assert time.monotonic() - start < 30.0


INTERRUPTED_CHILD = textwrap.dedent('''
    import sys, bearing_sim
    print('starting', flush=True)
    {call}
    print('finished', flush=True)
''')


@pytest.mark.parametrize('call', [
    'bearing_sim.generate({scenario!r}, duration_s=5000.0, allow_long_run=True)',
    'bearing_sim.simulate({bearing!r}, [1000.0, 0.0, 0.0], ring_speed_rad_s=100.0, duration_s=5000.0, '
    'allow_long_run=True)',
], ids=['generate', 'simulate'])
def test_ctrl_c_stops_a_long_run(call):
    code = INTERRUPTED_CHILD.format(call=call.format(scenario=scenario(), bearing=str(B6205)))
    child = subprocess.Popen([sys.executable, '-c', code], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=dict(os.environ))
    try:
        assert child.stdout.readline().strip() == 'starting'
        time.sleep(1.5)  # into the run (the load, the probe, the first samples)
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=20)
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert 'finished' not in out
    assert child.returncode != 0
    assert 'KeyboardInterrupt' in err, err


def test_static_equilibrium_refuses_a_cage_angle_whose_rounding_loses_the_balls():
    # 1e300 rad put every ball at one azimuth and gave a maximum ball load of 0.
    with pytest.raises(bearing_sim.InvalidInputError, match=r'cage angle 1e\+300 rad is beyond \+-1e\+06 rad'):
        bearing_sim.static_equilibrium(B6205, [1000.0, 0.0, 0.0], cage_angle_rad=1e300)
    # Within the limit the solution is the one a turn-reduced angle gives.
    near = bearing_sim.static_equilibrium(B6205, [1000.0, 0.0, 0.0], cage_angle_rad=0.1)
    far = bearing_sim.static_equilibrium(B6205, [1000.0, 0.0, 0.0], cage_angle_rad=0.1 + 2000.0 * 3.141592653589793)
    assert near['max_ball_load_N'] > 100.0
    assert far['max_ball_load_N'] == pytest.approx(near['max_ball_load_N'], rel=1e-6)


def test_modes_refuse_a_body_beyond_any_machine_naming_the_value_given():
    k = bearing_sim.static_equilibrium(B6205, [1000.0, 0.0, 0.0])['stiffness']
    with pytest.raises(bearing_sim.InvalidInputError, match=r'mass 1e-300 kg is outside \[0\.001, 1e\+07\] kg'):
        bearing_sim.modes(1e-300, [1.0, 1.0, 1.0], [(k, [0.0, 0.0, 0.0])])
    with pytest.raises(bearing_sim.InvalidInputError, match=r'support 2 position z -1e\+300 m is outside \[-100, 100\]'):
        bearing_sim.modes(1.0, [1.0, 1.0, 1.0], [(k, [0.0, 0.0, 1.0]), (k, [0.0, 0.0, -1e300])])


def test_a_speed_no_bearing_reaches_is_refused_by_every_call():
    # The 6205's pitch circle (39 mm) at 500 m/s: 25,600 rad/s; 1e300 rad/s gave numbers.
    b = bearing_sim.load_bearing(B6205)
    with pytest.raises(bearing_sim.InvalidInputError, match=r'1e\+300 rad/s .* is beyond \+-2\.56\de\+04 rad/s'):
        bearing_sim.frequencies(b, 1e300)
    with pytest.raises(bearing_sim.InvalidInputError, match=r'ring speed: 3e\+04 rad/s'):
        bearing_sim.simulate(b, [1000.0, 0.0, 0.0], ring_speed_rad_s=3e4, duration_s=0.01)
    with pytest.raises(bearing_sim.ConfigError, match=r'speed\.initial_speed_rpm.*beyond'):
        bearing_sim.generate(dict(scenario(), speed={'initial_speed_rpm': 1e12}))
    assert bearing_sim.frequencies(b, 2.5e4)['cage_hz'] > 0.0


def test_generate_refuses_a_scenario_whose_load_the_bearing_cannot_carry():
    # The node ran on at the last good load while the labels said 1e9 N: refused when read.
    steps = {'initial': {'force_N': [1000.0, 0.0, 0.0]},
             'segments': [{'type': 'step', 'start_s': 0.5, 'force_N': [1e9, 0.0, 0.0]}]}
    with pytest.raises(bearing_sim.ConfigError, match=r"load\.segments\[0\]\.force_N.*cannot carry the load \(1e\+09"):
        bearing_sim.generate(dict(scenario(), load=steps))

"""ct_gantry.launch ends by itself, with the reason on its output, when it cannot do what it
was asked: record:=true with a bag directory that cannot be created or written or has too
little free space (the recorder is required; record_bag checks before rosbag starts), and a
scenario whose player waits for a scenario_state subscriber that never comes (a bounded wait,
~wait_timeout_s), and model:= a name other than paper, rotor or flexible. That each model
starts its bearing file and publishes is checked here too. Each launch runs on a master of its own port; the tests wait for it to end
(at most LAUNCH_TIMEOUT_S, generous for a loaded machine) and never time it."""
import math
import os
import shutil
import signal
import socket
import subprocess
import time

import pytest

LAUNCH_TIMEOUT_S = 120


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


def launch(tmp_path, *args):
    """Runs `roslaunch bearing_sim ct_gantry.launch ARGS` until it ends; returns its output."""
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f'http://localhost:{port}', ROS_HOME=str(tmp_path / 'ros_home'),
               ROS_LOG_DIR=str(tmp_path / 'ros_home' / 'log'))
    roslaunch = shutil.which('roslaunch', path='/usr/bin:' + env.get('PATH', ''))
    p = subprocess.Popen([roslaunch, '-p', str(port), 'bearing_sim', 'ct_gantry.launch', 'viz:=false', *args],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
                         start_new_session=True)
    try:
        out, _ = p.communicate(timeout=LAUNCH_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGINT)
        out, _ = p.communicate(timeout=60)
        pytest.fail(f'the launch did not end by itself within {LAUNCH_TIMEOUT_S} s:\n{out[-4000:]}')
    return out


def unwritable_dir(tmp_path):
    """An existing directory in which this user cannot create a file (root writes anywhere
    permissions allow, but not into sysfs)."""
    if os.geteuid() == 0:
        return '/sys'
    d = tmp_path / 'read_only'
    d.mkdir(mode=0o555)
    return str(d)


def bag_dir_and_reason(tmp_path, case):
    """bag_dir, more launch arguments and the line record_bag must print."""
    if case == 'uncreatable':
        (tmp_path / 'a_file').write_text('')
        bag_dir = str(tmp_path / 'a_file' / 'bags')
        return bag_dir, [], f'record_bag: cannot create the bag directory {bag_dir} (Not a directory): not recording'
    if case == 'unwritable':
        bag_dir = unwritable_dir(tmp_path)
        return bag_dir, [], f'record_bag: cannot create a file in {bag_dir} ('
    st = os.statvfs(tmp_path)
    asked = 2 * st.f_bavail * st.f_frsize // (1 << 20) + 1024
    bag_dir = str(tmp_path / 'bags')
    return bag_dir, [f'bag_min_free_mb:={asked}'], f'MB free, less than the {asked} MB asked for (bag_min_free_mb)'


@pytest.mark.parametrize('case', ['uncreatable', 'unwritable', 'no room'])
def test_a_recorder_that_cannot_record_ends_the_launch_with_the_reason(tmp_path, case):
    bag_dir, extra, reason = bag_dir_and_reason(tmp_path, case)
    out = launch(tmp_path, 'record:=true', f'bag_dir:={bag_dir}', *extra)
    assert reason in out, out[-4000:]
    assert 'REQUIRED process [bearing/recorder' in out, out[-4000:]
    if case == 'no room':  # created, and left empty: no bag of 4 kB without messages, no probe file
        assert os.listdir(bag_dir) == []


def test_a_scenario_with_a_recorder_that_cannot_record_ends(tmp_path):
    # The player waits for the recorder's subscription to scenario_state; the recorder is
    # required, so the launch ends when it dies instead of when the player gives up.
    bag_dir = str(tmp_path / 'a_file' / 'bags')
    (tmp_path / 'a_file').write_text('')
    out = launch(tmp_path, 'record:=true', f'bag_dir:={bag_dir}', 'scenario:=ct_gantry_scan',
                 'scenario_shutdown:=true')
    assert f'record_bag: cannot create the bag directory {bag_dir}' in out, out[-4000:]
    assert 'REQUIRED process [bearing/recorder' in out, out[-4000:]


def test_the_scenario_player_waits_a_bounded_time_and_names_what_is_missing(tmp_path):
    out = launch(tmp_path, 'scenario:=ct_gantry_scan', 'scenario_shutdown:=true',
                 'scenario_wait_for_subscribers:=1', 'scenario_wait_timeout_s:=3')
    assert 'scenario_player: waiting up to 3 s (~wait_timeout_s) for /bearing/bearing_sim_node and 1 subscriber(s) ' \
           'of /bearing/scenario_state' in out, out[-4000:]
    assert 'scenario_player: after 3 s (~wait_timeout_s), /bearing/scenario_state has 0 of the 1 subscriber(s) ' \
           'asked for' in out, out[-4000:]
    assert 'REQUIRED process [bearing/scenario_player' in out, out[-4000:]


def test_the_scenario_player_refuses_an_unbounded_wait(tmp_path):
    out = launch(tmp_path, 'scenario:=ct_gantry_scan', 'scenario_shutdown:=true', 'scenario_wait_timeout_s:=0')
    assert 'scenario_player: ~wait_timeout_s must be a finite number of seconds > 0, got 0' in out, out[-4000:]
    assert 'REQUIRED process [bearing/scenario_player' in out, out[-4000:]


def test_an_unknown_model_stops_the_launch_naming_the_choices(tmp_path):
    out = launch(tmp_path, 'model:=rigid')
    assert "arg 'model:=rigid, choose paper, rotor or flexible' is not defined" in out, out[-4000:]


def ros_command(env, *args, timeout):
    """Runs a ROS command line tool (rostopic, rosparam) on the launch's master, retried until
    the master and the topic are there or `timeout` s have passed; returns its output."""
    tool = shutil.which(args[0], path='/usr/bin:' + env.get('PATH', ''))
    deadline = time.monotonic() + timeout
    while True:
        r = subprocess.run([tool, *args[1:]], env=env, capture_output=True, text=True,
                           timeout=max(deadline - time.monotonic(), 1.0))
        if r.returncode == 0 or time.monotonic() > deadline:
            return r.stdout + r.stderr
        time.sleep(1.0)


def check_ring_deformation(text):
    """A RingDeformation message (rostopic's YAML) is the CT ring's modal sum: 72 azimuths evenly
    spaced, and radial and axial displacements made of the ring's orders n = 2..6 only (its
    flexible_ring block's in_plane_max_order and out_of_plane_max_order), loaded: micrometres."""
    import numpy
    import yaml
    msg = yaml.safe_load(text.split('---')[0])
    azimuth = numpy.array(msg['azimuth'])
    assert len(azimuth) == 72, text[:2000]
    assert numpy.allclose(azimuth, 2 * numpy.pi * numpy.arange(72) / 72, atol=1e-6)
    for key in ('radial', 'axial'):
        w = numpy.array(msg[key])
        spectrum = numpy.abs(numpy.fft.rfft(w)) / len(w)
        in_orders = spectrum[2:7].max()
        # Float32 values: other orders at rounding, 1e-6 of the ring's own with margin.
        assert numpy.delete(spectrum, range(2, 7)).max() < 1e-6 * in_orders, (key, spectrum)
    assert 1e-6 < numpy.abs(msg['radial']).max() < 1e-4, msg['radial']  # m: the loaded ring's micrometres


@pytest.mark.parametrize('model, bearing_file', [('paper', 'ct_gantry_lyc.yaml'), ('rotor', 'ct_gantry_physical.yaml'),
                                                 ('flexible', 'ct_gantry_flexible.yaml')])
def test_each_model_runs_its_bearing_file_and_publishes(tmp_path, model, bearing_file):
    # As fast as possible, so that a loaded machine only makes it slower; a finite level is
    # published once the dynamics run.
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f'http://localhost:{port}', ROS_HOME=str(tmp_path / 'ros_home'),
               ROS_LOG_DIR=str(tmp_path / 'ros_home' / 'log'))
    roslaunch = shutil.which('roslaunch', path='/usr/bin:' + env.get('PATH', ''))
    p = subprocess.Popen([roslaunch, '-p', str(port), 'bearing_sim', 'ct_gantry.launch', 'viz:=false',
                          'real_time:=false', f'model:={model}'], stdout=subprocess.DEVNULL,
                         stderr=subprocess.STDOUT, start_new_session=True, env=env)
    try:
        param = ros_command(env, 'rosparam', 'get', '/bearing/bearing_sim_node/bearing_file',
                            timeout=LAUNCH_TIMEOUT_S)
        assert param.strip().endswith('/config/bearings/' + bearing_file), param
        level = ros_command(env, 'rostopic', 'echo', '-n', '1', '/bearing/vibration_level/level_db',
                            timeout=LAUNCH_TIMEOUT_S)
        value = float(level.split()[0])
        assert math.isfinite(value), level  # L of a running dynamics (-inf before any sample)
        if model == 'flexible':
            check_ring_deformation(ros_command(env, 'rostopic', 'echo', '-n', '1', '/bearing/ring_deformation',
                                               timeout=LAUNCH_TIMEOUT_S))
    finally:
        os.killpg(p.pid, signal.SIGINT)
        p.wait(timeout=60)

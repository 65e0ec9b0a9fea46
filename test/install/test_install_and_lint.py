#!/usr/bin/env python3
"""The package as a user gets it, from a configured and built build directory.

- catkin_lint (default level) reports no error and no warning, and the only messages the
  CMakeLists ignores on purpose are those of the development programs and scripts it names
  (skipped, and said so, when catkin_lint is not installed).
- `cmake --install` into a temporary directory (DESTDIR), then, in a clean environment that
  sources only that install space's setup.bash:
    * the install space holds the library, headers, nodes, tools, scripts and every file of
      launch/, config/, rviz/ and cfg/, and the programs load the installed core library;
    * `rosrun bearing_sim bearing_tool frequencies` answers the closed-form kinematic
      frequencies of the installed CT gantry bearing file, and so does the installed Python
      module (`import bearing_sim`, the pybind11 core beside the generated messages);
    * `roslaunch bearing_sim ct_gantry.launch` streams vibration: chunks whose stamps are
      their sample index over the sample rate, finite accelerations that are not all zero,
      published by a process that runs the installed code.

Writes a JUnit result file (--results); `--listen` is the subscriber it runs in the
install space's environment.
"""
import argparse
import json
import math
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest
import xml.etree.ElementTree as ET

ARGS = None

# Programs and scripts that run on the source or build tree only (CMakeLists.txt says why);
# catkin_lint's messages about them are ignored there on purpose, and only those.
DEVELOPMENT_ONLY = {
    'UNINSTALLED_TARGET': {'bearing_sim_bench_simulate', 'bearing_sim_bench_sensor', 'bearing_sim_bench_lcm_bridge',
                           'bearing_sim_integrator_study'},
    'UNINSTALLED_SCRIPT': {'scripts/setup_and_run.sh', 'dev/cwru_indicators.py',
                           'dev/build.sh', 'dev/install_deps.sh', 'dev/capture_rviz_screenshot.sh',
                           'dev/make_validation.py', 'dev/compare_builds.sh', 'dev/slurm_campaign.sh',
                           'bench/bench_generate.sh', 'bench/bench_campaign.py'},
}

# scripts/ holds what is installed for users; beside it only the README's two commands and the
# env.sh they source (development scripts are in dev/).
SCRIPTS_NOT_INSTALLED = {'setup_and_run.sh', 'setup_and_test.sh', 'env.sh'}

# Generous bounds: the test waits on events, it does not measure speed.
LAUNCH_TIMEOUT_S = 240.0
CHUNKS_WANTED = 200  # 2 s of the 10 kHz stream in chunks of 100 samples


def cache_value(build_dir, key):
    with open(os.path.join(build_dir, 'CMakeCache.txt')) as f:
        for line in f:
            if line.startswith(key + ':'):
                return line.split('=', 1)[1].strip()
    return None


class CatkinLint(unittest.TestCase):
    def run_lint(self, *options):
        r = subprocess.run(['catkin_lint', '--output', 'json', *options, ARGS.source_dir],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300)
        self.assertIn(r.returncode, (0, 1), r.stderr)
        return json.loads(r.stdout)

    def setUp(self):
        if shutil.which('catkin_lint') is None:
            print('SKIPPED: catkin_lint is not installed (Debian catkin-lint)', flush=True)
            self.skipTest('catkin_lint is not installed (Debian catkin-lint)')

    def test_no_error_and_no_warning(self):
        report = self.run_lint()
        problems = report['errors'] + report['warnings']
        self.assertEqual(problems, [], '\n'.join(f"{p['id']}: {p['text']}" for p in problems))

    def test_only_the_named_development_files_are_ignored(self):
        report = self.run_lint('--show-ignored')
        for p in report['errors'] + report['warnings']:
            allowed = DEVELOPMENT_ONLY.get(p['id'], set())
            self.assertTrue(any(f"'{name}'" in p['text'] for name in allowed), f"{p['id']}: {p['text']}")


class InstallSpace(unittest.TestCase):
    """One install for all cases (setUpClass), removed at the end."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='bearing_sim_install_')
        destdir = os.path.join(cls.tmp, 'destdir')
        prefix = cache_value(ARGS.build_dir, 'CMAKE_INSTALL_PREFIX')
        cls.with_lcm = cache_value(ARGS.build_dir, 'BEARING_SIM_WITH_LCM') != 'OFF'
        cls.prefix = os.path.normpath(destdir + prefix)
        r = subprocess.run(['cmake', '--install', ARGS.build_dir], env=dict(os.environ, DESTDIR=destdir),
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
        cls.install_log = r.stdout
        cls.install_ok = r.returncode == 0
        os.makedirs(os.path.join(cls.tmp, 'home'))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def setUp(self):
        self.assertTrue(self.install_ok, 'cmake --install failed:\n' + self.install_log[-3000:])

    def clean_env(self, port=None):
        # Nothing of the calling shell (devel space, source tree): only what setup.bash sets.
        env = {'HOME': os.path.join(self.tmp, 'home'), 'PATH': '/usr/bin:/bin', 'LANG': 'C.UTF-8',
               'ROS_HOME': os.path.join(self.tmp, 'ros_home'), 'ROS_HOSTNAME': 'localhost'}
        if port is not None:
            env['ROS_MASTER_URI'] = f'http://localhost:{port}'
        return env

    def in_install_space(self, argv, port=None, **kwargs):
        command = ['bash', '-c', 'source "$0/setup.bash" && exec "$@"', self.prefix, *argv]
        return subprocess.run(command, env=self.clean_env(port), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True, **kwargs)

    def test_rospack_finds_the_installed_package(self):
        r = self.in_install_space(['rospack', 'find', 'bearing_sim'], timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(os.path.realpath(r.stdout.strip()),
                         os.path.realpath(os.path.join(self.prefix, 'share', 'bearing_sim')))

    def test_everything_a_user_runs_or_reads_is_installed(self):
        programs = ['bearing_sim_node', 'bearing_viz_node', 'scenario_player', 'bearing_tool', 'record_bag',
                    'soak_node.py', 'measure_node.py', 'measure_lcm_bridge.py', 'bearing_campaign', 'cm_benchmark']
        files = ['lib/libbearing_sim_core.so', 'include/bearing_sim/core/bearing_model.hpp',
                 'include/bearing_sim/VibrationChunk.h', 'share/bearing_sim/package.xml',
                 'share/bearing_sim/msg/VibrationChunk.msg', 'share/bearing_sim/srv/InjectDefect.srv']
        if self.with_lcm:
            programs += ['lcm_bridge', 'lcm_consumer_example']
            files += [f'share/bearing_sim/lcm/{f}' for f in os.listdir(os.path.join(ARGS.source_dir, 'lcm'))]
        for p in programs:
            path = os.path.join(self.prefix, 'lib', 'bearing_sim', p)
            self.assertTrue(os.access(path, os.X_OK), f'{path} is not an installed program')
        for d in ('launch', 'config', 'rviz', 'cfg'):
            for root, _, names in os.walk(os.path.join(ARGS.source_dir, d)):
                for n in names:
                    files.append(os.path.join('share', 'bearing_sim', os.path.relpath(os.path.join(root, n),
                                                                                       ARGS.source_dir)))
        missing = [f for f in files if not os.path.isfile(os.path.join(self.prefix, f))]
        self.assertEqual(missing, [])

    def test_scripts_holds_only_what_is_installed(self):
        scripts = os.path.join(ARGS.source_dir, 'scripts')
        for name in sorted(os.listdir(scripts)):
            if name in SCRIPTS_NOT_INSTALLED or name == '__pycache__':
                continue
            path = os.path.join(self.prefix, 'lib', 'bearing_sim', name)
            self.assertTrue(os.access(path, os.X_OK), f'scripts/{name} is not installed (a development script '
                                                      'belongs in dev/)')

    def test_programs_load_the_installed_core_library(self):
        core = os.path.join(self.prefix, 'lib', 'libbearing_sim_core.so')
        for p in ('bearing_sim_node', 'bearing_viz_node', 'scenario_player', 'bearing_tool'):
            r = self.in_install_space(['ldd', os.path.join(self.prefix, 'lib', 'bearing_sim', p)], timeout=60)
            line = next((l for l in r.stdout.splitlines() if 'libbearing_sim_core.so' in l), '')
            resolved = line.split('=>')[-1].split('(')[0].strip()
            self.assertTrue(os.path.exists(resolved) and os.path.samefile(resolved, core), f'{p}: {line or r.stdout}')

    def closed_form_frequencies(self, f_o):
        """Rolling without slip, outer ring at f_o, inner fixed (docs/model.md, kinematic
        frequencies): gamma = d cos(alpha) / d_m, cage f_o (1 + gamma) / 2, and each race
        sees Z balls per row pass at its speed relative to the cage."""
        import yaml  # python3-yaml, a dependency of rospy
        with open(self.ct_bearing_file()) as f:
            b = yaml.safe_load(f)
        gamma = b['ball_diameter_mm'] * math.cos(math.radians(b['contact_angle_deg'])) / b['pitch_diameter_mm']
        z = b['balls_per_row']
        return {'relative_ring_hz': f_o, 'cage_hz': f_o * (1 + gamma) / 2,
                'ball_pass_outer_race_hz': z * f_o * (1 - gamma) / 2,
                'ball_pass_inner_race_hz': z * f_o * (1 + gamma) / 2}

    def ct_bearing_file(self):
        return os.path.join(self.prefix, 'share', 'bearing_sim', 'config', 'bearings', 'ct_gantry_lyc.yaml')

    def test_bearing_tool_frequencies_match_the_closed_form(self):
        r = self.in_install_space(['rosrun', 'bearing_sim', 'bearing_tool', 'frequencies', '--bearing',
                                   self.ct_bearing_file(), '--outer-rpm', '180', '--inner-rpm', '0', '--json'],
                                  timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        result = json.loads(r.stdout)
        for key, value in self.closed_form_frequencies(180.0 / 60.0).items():
            self.assertAlmostEqual(result[key], value, delta=1e-9 * value, msg=key)

    def test_python_module_imports_from_the_install_space(self):
        # The pybind11 module bearing_sim._core beside the generated messages, both from the
        # install space; the CT bearing's outer ring at 180 rpm gives the closed form.
        script = ('import json, math, sys, bearing_sim, bearing_sim._core\n'
                  'from bearing_sim.msg import VibrationChunk\n'
                  'f = bearing_sim.frequencies(sys.argv[1], 2 * math.pi * 3.0)\n'
                  'print(json.dumps({"package": bearing_sim.__file__, "core": bearing_sim._core.__file__,'
                  ' "msg": sys.modules[VibrationChunk.__module__].__file__, "frequencies": f}))\n')
        r = self.in_install_space(['python3', '-c', script, self.ct_bearing_file()], timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        result = json.loads(r.stdout.strip().splitlines()[-1])
        installed = os.path.realpath(self.prefix) + os.sep
        for key in ('package', 'core', 'msg'):
            self.assertTrue(os.path.realpath(result[key]).startswith(installed), f'{key}: {result[key]}')
        for key, value in self.closed_form_frequencies(3.0).items():
            self.assertAlmostEqual(result['frequencies'][key], value, delta=1e-9 * value, msg=key)

    def test_python_entry_points_run_from_the_install_space(self):
        # Thin scripts over the installed module (no --help here: setup.bash would take it).
        # bearing_campaign without arguments: its own usage, so the module imported.
        r = self.in_install_space(['rosrun', 'bearing_sim', 'bearing_campaign'], timeout=120)
        self.assertEqual(r.returncode, 2, r.stderr[-3000:])
        self.assertIn('usage: bearing_campaign', r.stderr)
        # cm_benchmark: one case of the quick grid, its bearing and sensor from the installed config/.
        out = os.path.join(self.tmp, 'cm_benchmark')
        r = self.in_install_space(['rosrun', 'bearing_sim', 'cm_benchmark', '--quick', '--limit', '1', '--workers', '0',
                                   '--out', out], timeout=300)
        self.assertEqual(r.returncode, 0, r.stdout[-3000:] + r.stderr[-3000:])
        with open(os.path.join(out, 'summary.json')) as f:
            summary = json.load(f)
        self.assertEqual((summary['cases'], summary['errors']), (1, 0))

    def test_roslaunch_ct_gantry_streams_vibration(self):
        with socket.socket() as s:  # a free port for this test's own ROS master
            s.bind(('localhost', 0))
            port = s.getsockname()[1]
        log_path = os.path.join(self.tmp, 'roslaunch.log')
        with open(log_path, 'w') as log:
            command = ['bash', '-c', 'source "$0/setup.bash" && exec "$@"', self.prefix,
                       'roslaunch', '-p', str(port), 'bearing_sim', 'ct_gantry.launch', 'rviz:=false']
            launch = subprocess.Popen(command, env=self.clean_env(port), stdout=log, stderr=subprocess.STDOUT,
                                      start_new_session=True)
        try:
            r = self.in_install_space(['python3', os.path.abspath(__file__), '--listen'],
                                      port=port, timeout=LAUNCH_TIMEOUT_S + 60)
        finally:
            os.killpg(launch.pid, signal.SIGINT)
            try:
                launch.wait(timeout=60)
            except subprocess.TimeoutExpired:
                os.killpg(launch.pid, signal.SIGKILL)
                launch.wait()
        with open(log_path) as f:
            launch_log = f.read()[-3000:]
        self.assertEqual(r.returncode, 0, f'listener: {r.stderr[-3000:]}\nroslaunch:\n{launch_log}')
        s = json.loads(r.stdout.strip().splitlines()[-1])
        self.assertGreaterEqual(s['chunks'], CHUNKS_WANTED, launch_log)
        self.assertEqual(s['sample_rate'], [10000.0])
        self.assertEqual(s['ragged_chunks'], 0)
        self.assertEqual(s['nonfinite_samples'], 0)
        # Simulated time is the sample index over the rate: stamps and counters agree to the ns.
        self.assertLess(s['max_stamp_error_s'], 2e-9)
        # A loaded, turning bearing vibrates (ball passage at about 300 Hz at least).
        self.assertGreater(s['accel_rms'], 0.0)
        # The publishing process runs the installed core library, and no other copy of it.
        installed_core = os.path.realpath(os.path.join(self.prefix, 'lib', 'libbearing_sim_core.so'))
        self.assertEqual(s['publisher_core_libraries'], [installed_core], s['publisher'])


def listen():
    """Runs in the install space's environment: subscribes to /bearing/vibration, prints a summary."""
    import threading
    import xmlrpc.client

    import rosgraph
    import rospy
    from bearing_sim.msg import VibrationChunk

    chunks = []
    done = threading.Event()

    def on_chunk(m):
        chunks.append((m.header.stamp.to_nsec(), m.first_sample, m.sample_rate, list(m.accel_x), len(m.accel_y),
                       len(m.accel_z)))
        if len(chunks) >= CHUNKS_WANTED:
            done.set()

    rospy.init_node('install_test_listener', anonymous=True, disable_signals=True)
    rospy.Subscriber('/bearing/vibration', VibrationChunk, on_chunk, queue_size=1000)
    if not done.wait(LAUNCH_TIMEOUT_S):
        sys.exit(f'only {len(chunks)} of {CHUNKS_WANTED} vibration chunks within {LAUNCH_TIMEOUT_S} s')
    data = chunks[:CHUNKS_WANTED]
    t0, n0, rate = data[0][0], data[0][1], data[0][2]
    values = [v for c in data for v in c[3]]
    finite = [v for v in values if math.isfinite(v)]
    mean = sum(finite) / max(len(finite), 1)
    master = rosgraph.Master('/install_test_listener')
    publishers = dict(master.getSystemState()[0]).get('/bearing/vibration', [])
    core_libraries = set()
    if publishers:
        _, _, pid = xmlrpc.client.ServerProxy(master.lookupNode(publishers[0])).getPid('/install_test_listener')
        with open(f'/proc/{pid}/maps') as f:
            core_libraries = {os.path.realpath(line.split()[-1]) for line in f
                              if line.rstrip().endswith('/libbearing_sim_core.so')}
    print(json.dumps({
        'chunks': len(data),
        'samples': len(values),
        'sample_rate': sorted({c[2] for c in data}),
        'ragged_chunks': sum(1 for c in data if not len(c[3]) == c[4] == c[5] > 0),
        'nonfinite_samples': len(values) - len(finite),
        'max_stamp_error_s': max(abs((c[0] - t0) * 1e-9 - (c[1] - n0) / rate) for c in data),
        'accel_rms': math.sqrt(sum((v - mean) ** 2 for v in finite) / max(len(finite), 1)),
        'publisher': publishers,
        'publisher_core_libraries': sorted(core_libraries),
    }), flush=True)
    rospy.signal_shutdown('done')


def write_junit(result, path, elapsed):
    suite = ET.Element('testsuite', name='install_and_lint', tests=str(result.testsRun),
                       failures=str(len(result.failures)), errors=str(len(result.errors)),
                       skipped=str(len(result.skipped)), time=f'{elapsed:.1f}')
    outcome = {id(t): ('failure', m) for t, m in result.failures}
    outcome.update({id(t): ('error', m) for t, m in result.errors})
    outcome.update({id(t): ('skipped', m) for t, m in result.skipped})
    for test in result.ran:
        case = ET.SubElement(suite, 'testcase', classname=type(test).__name__, name=test._testMethodName)
        if id(test) in outcome:
            kind, message = outcome[id(test)]
            ET.SubElement(case, kind, message=message.strip().splitlines()[-1][:400]).text = message
    os.makedirs(os.path.dirname(path), exist_ok=True)
    ET.ElementTree(suite).write(path, encoding='utf-8', xml_declaration=True)


class RecordingResult(unittest.TextTestResult):
    def __init__(self, *a, **k):
        super().__init__(*a, **k)
        self.ran = []

    def startTest(self, test):
        self.ran.append(test)
        super().startTest(test)


def main():
    global ARGS
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--source-dir')
    p.add_argument('--build-dir')
    p.add_argument('--results')
    p.add_argument('--listen', action='store_true', help=argparse.SUPPRESS)
    ARGS = p.parse_args()
    if ARGS.listen:
        listen()
        return 0
    suite = unittest.TestSuite()
    loader = unittest.defaultTestLoader
    suite.addTests(loader.loadTestsFromTestCase(CatkinLint))
    suite.addTests(loader.loadTestsFromTestCase(InstallSpace))
    start = time.monotonic()
    result = unittest.TextTestRunner(verbosity=2, resultclass=RecordingResult, stream=sys.stdout).run(suite)
    write_junit(result, ARGS.results, time.monotonic() - start)
    return 0 if result.wasSuccessful() else 1


if __name__ == '__main__':
    sys.exit(main())

"""The layers: core -> runtime -> {ROS nodes, bearing_tool, Python}. The core and the runtime
include no ROS header (roscpp, messages, rosbag, nodelet, pluginlib, dynamic_reconfigure, tf2,
the package's generated messages or its ROS side), and the core nothing of the runtime. Their
libraries are also compiled without catkin's include directories (CMakeLists.txt), but Debian
installs ROS headers in /usr/include, where the compiler finds them anyway: hence this scan."""
import re

from conftest import SOURCE

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.MULTILINE)

# Directories and headers of ROS 1 packages (angle or quoted).
ROS_PREFIXES = ('ros/', 'rosbag/', 'rosgraph_msgs/', 'roscpp/', 'rostime/', 'nodelet/', 'pluginlib/',
                'dynamic_reconfigure/', 'tf/', 'tf2/', 'tf2_ros/', 'xmlrpcpp/', 'diagnostic_updater/',
                'message_filters/', 'actionlib/', 'image_transport/', 'class_loader/', 'bearing_sim_lcm/', 'lcm/')
ROS_HEADERS = ('ros.h', 'XmlRpc.h', 'XmlRpcValue.h')
# The package's own headers a layer may include.
ALLOWED_OWN = {
    'core': ('bearing_sim/core/',),
    'runtime': ('bearing_sim/core/', 'bearing_sim/runtime/'),
}


def ros_include(header):
    """Why `header` is a ROS header, or '' if it is not."""
    if header.startswith(ROS_PREFIXES) or header in ROS_HEADERS:
        return 'a ROS package header'
    if re.match(r'^[A-Za-z0-9_]+_msgs/', header) or re.match(r'^[A-Za-z0-9_]+_srvs/', header):
        return 'a ROS message header'
    return ''


def violations(layer, text):
    """(header, reason) of every include of `text` the layer may not have."""
    found = []
    for _, header in INCLUDE.findall(text):
        reason = ros_include(header)
        if not reason and header.startswith('bearing_sim/') and not header.startswith(ALLOWED_OWN[layer]):
            # bearing_sim/Foo.h: a generated message; bearing_sim/ros, viz: the ROS side.
            reason = 'not of the layer or below it (the core, the runtime)'
        if reason:
            found.append((header, reason))
    return found


def layer_files(layer):
    files = []
    for root in (SOURCE / 'include' / 'bearing_sim' / layer, SOURCE / 'src' / layer):
        files += [p for p in root.rglob('*') if p.suffix in ('.h', '.hpp', '.cpp', '.cc')]
    return sorted(files)


def test_the_check_finds_a_ros_include_a_generated_message_and_an_upward_include():
    text = ('#include <vector>\n#include <ros/ros.h>\n#include "bearing_sim/VibrationChunk.h"\n'
            '#include <geometry_msgs/Wrench.h>\n#include "bearing_sim/ros/message_conversion.hpp"\n'
            '#include "bearing_sim/core/scenario.hpp"\n#include "bearing_sim/runtime/sample_pipeline.hpp"\n'
            '#include <rosbag/bag.h>\n#include <Eigen/Dense>\n')
    assert [h for h, _ in violations('runtime', text)] == [
        'ros/ros.h', 'bearing_sim/VibrationChunk.h', 'geometry_msgs/Wrench.h', 'bearing_sim/ros/message_conversion.hpp',
        'rosbag/bag.h'
    ]
    # The core may not include the runtime, which is above it.
    assert 'bearing_sim/runtime/sample_pipeline.hpp' in [h for h, _ in violations('core', text)]


def test_core_and_runtime_include_no_ros_header():
    problems = []
    for layer in ('core', 'runtime'):
        files = layer_files(layer)
        assert len(files) > 10, f'{layer}: the layer\'s sources were not found under {SOURCE}'
        for path in files:
            for header, reason in violations(layer, path.read_text(encoding='utf-8')):
                problems.append(f'{path.relative_to(SOURCE)} includes {header}: {reason}')
    assert not problems, '\n'.join(problems)


# The public core headers are the physics and the types of its inputs: the YAML readers behind
# them (bearing file, imperfections, sensor, scenario, sweep) are private to src/core.
YAML_TYPE = re.compile(r'\bYAML::')
LINE_COMMENT = re.compile(r'//[^\n]*')


def yaml_exposures(text):
    """Every yaml-cpp include of a header's text, and 'YAML::' if its code names a yaml-cpp type."""
    found = [h for _, h in INCLUDE.findall(text) if h.startswith('yaml-cpp/')]
    if YAML_TYPE.search(LINE_COMMENT.sub('', text)):
        found.append('YAML::')
    return found


def test_the_yaml_check_finds_an_include_and_a_type_but_not_a_comment():
    assert yaml_exposures('#include <string>\n#include <yaml-cpp/yaml.h>\n') == ['yaml-cpp/yaml.h']
    assert yaml_exposures('#include "yaml-cpp/node/node.h"\n') == ['yaml-cpp/node/node.h']
    assert yaml_exposures('Config parse(const YAML::Node& root);\n') == ['YAML::']
    assert yaml_exposures('// read from a YAML file (see YAML::Node in src/core)\nint rows = 1;\n') == []


def test_public_core_headers_expose_no_yaml():
    headers = sorted((SOURCE / 'include' / 'bearing_sim' / 'core').glob('*.hpp'))
    assert len(headers) > 10, f'the core\'s public headers were not found under {SOURCE}'
    problems = [f'{path.relative_to(SOURCE)}: {found}' for path in headers
                for found in yaml_exposures(path.read_text(encoding='utf-8'))]
    assert not problems, 'a public core header exposes yaml-cpp:\n' + '\n'.join(problems)


# The core's sources that read YAML: the readers, and the sweep (it varies a bearing file's
# keys for each case). The physics sources include no yaml-cpp, directly or through a core header.
READER_NAME = re.compile(r'(_reader|_yaml)\.(hpp|cpp)$|^yaml_')
YAML_SOURCES = {
    'sweep.cpp': 'varies the keys of a bearing file for each case',
    'flexible_ring_config.cpp': 'the reader of the flexible_ring: block',
    'flexible_ring_config.hpp': 'the reader of the flexible_ring: block',
}


def core_yaml_users():
    """Names of the src/core files that include yaml-cpp, directly or through src/core's headers."""
    core = SOURCE / 'src' / 'core'
    includes = {p.name: [h for _, h in INCLUDE.findall(p.read_text(encoding='utf-8'))]
                for p in core.iterdir() if p.suffix in ('.hpp', '.cpp')}
    users = {name for name, headers in includes.items() if any(h.startswith('yaml-cpp/') for h in headers)}
    grown = True
    while grown:
        grown = False
        for name, headers in includes.items():
            if name not in users and any(h in users for h in headers):
                users.add(name)
                grown = True
    return users


def test_core_physics_sources_read_no_yaml():
    users = core_yaml_users()
    assert 'yaml_reader.hpp' in users and 'scenario_reader.cpp' in users, 'the scan found no reader'
    problems = sorted(name for name in users if not READER_NAME.search(name) and name not in YAML_SOURCES)
    assert not problems, ('core sources that are not readers include yaml-cpp (move the reading to a '
                          '*_reader.cpp): ' + ', '.join(problems))
    gone = sorted(name for name in YAML_SOURCES if name not in users)
    assert not gone, 'no longer reading YAML, drop from YAML_SOURCES: ' + ', '.join(gone)

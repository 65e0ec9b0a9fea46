"""Files of the package's config/ directory, wherever the package runs from.

In the devel space this module is the source tree's python/bearing_sim/config_files.py
(catkin's __init__ points there), so config/ is two levels up. Installed, config/ is
share/bearing_sim/config, which ROS finds through rospkg or ROS_PACKAGE_PATH."""
import os
import pathlib

PACKAGE = 'bearing_sim'


def _package_dirs():
    yield pathlib.Path(__file__).resolve().parents[2]  # the source tree
    try:
        import rospkg
        yield pathlib.Path(rospkg.RosPack().get_path(PACKAGE))
    except Exception:  # rospkg missing, or the package not on its path
        pass
    for entry in os.environ.get('ROS_PACKAGE_PATH', '').split(os.pathsep):
        # An entry is a package itself or a directory of packages (share/).
        for candidate in (pathlib.Path(entry), pathlib.Path(entry) / PACKAGE):
            if entry and _is_this_package(candidate):
                yield candidate


def _is_this_package(directory):
    try:
        return f'<name>{PACKAGE}</name>' in (directory / 'package.xml').read_text(encoding='utf-8')
    except OSError:
        return False


def config_file(relative):
    """Path of config/<relative> (e.g. 'bearings/cwru_6205_drive_end.yaml'); FileNotFoundError
    naming the places looked in when none has it."""
    tried = []
    for package_dir in _package_dirs():
        candidate = package_dir / 'config' / relative
        if candidate.is_file():
            return candidate
        if str(candidate.parent) not in tried:
            tried.append(str(candidate.parent))
    raise FileNotFoundError(f"config/{relative} of {PACKAGE} not found (looked in: {', '.join(tried)})")
